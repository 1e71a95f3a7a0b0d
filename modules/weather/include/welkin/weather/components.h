#pragma once
// The weather module's component: a METAR report that sets the scene's sky. When the report (or its
// date or place) changes, the module's system writes the scene's cloud layers, haze, clock and
// place from it (welkin/weather/sky_from_metar.h), adding a time of day, clouds or an atmosphere the
// scene lacks; between changes the scene's values are its own (the editor may tune them).
#include <string>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin::weather {

// Where the scene stands: `automatic` keeps the scene's time of day's place when it has one and
// takes the station's from the table otherwise; `station` always takes the station's; `scene` never.
enum class ReportPlace : int { automatic = 0, station = 1, scene = 2 };

struct Report {
  static constexpr std::string_view kTypeName = "weather.Report";
  std::string metar;  // the report (METAR or SPECI); empty: none
  int year = 0;       // a report gives only the day: 0 keeps the time of day's year and month
  int month = 0;
  ReportPlace place = ReportPlace::automatic;
};
void describe(TypeBuilder<Report>& t);

}  // namespace welkin::weather
