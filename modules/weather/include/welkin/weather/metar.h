#pragma once
// METAR and SPECI reports (WMO No. 306 FM 15/FM 16, as the FAA's AIM 7-1-30 explains them),
// decoded strictly: every group up to the remarks must be one the format defines, in its place, or
// the report is refused with one error naming the group and where it stands. Remarks (RMK) and the
// trend forecast (NOSIG, BECMG, TEMPO) are observations' annexes and are skipped.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace welkin::weather {

// A report longer than this is refused before it is read (the longest real ones are about 300).
inline constexpr size_t kMaxMetarBytes = 1024;

struct MetarWind {
  std::optional<int> direction_deg;  // where it blows from, true north; absent: variable (VRB)
  double speed_mps = 0.0;            // mean over the last 10 minutes
  std::optional<double> gust_mps;
  std::optional<int> variable_from_deg, variable_to_deg;  // the dddVddd sector
  double speed_as_reported = 0.0;                         // in the report's unit (knots, m/s or km/h)
  std::string unit;                                       // "KT", "MPS" or "KMH"
};

struct MetarVisibility {
  double metres = 0.0;         // prevailing visibility
  bool at_least = false;       // 9999, P6SM, CAVOK: this much or more
  bool less_than = false;      // M1/4SM
  bool statute_miles = false;  // reported in SM (metres converted at 1609.344)
};

// One present-weather group: intensity, a descriptor, one or more phenomena (-SHRA, TSRA, BR).
struct MetarWeather {
  std::string intensity;               // "-", "+", "VC" (in the vicinity) or "" (moderate)
  std::string descriptor;              // MI BC PR DR BL SH TS FZ, or ""
  std::vector<std::string> phenomena;  // DZ RA SN ... BR FG HZ ...
  std::string text;                    // the group as written
  bool has(std::string_view phenomenon) const;
};

enum class CloudCover { few, scattered, broken, overcast, vertical_visibility };

// One cloud group: amount and base (FEW008 = few at 800 ft), or VVhhh (sky obscured).
struct MetarCloud {
  CloudCover cover = CloudCover::few;
  int base_ft = 0;        // above the aerodrome
  std::string type;       // "CB", "TCU" or ""
  int oktas_min() const;  // FEW 1, SCT 3, BKN 5, OVC 8 (VV: 8)
  int oktas_max() const;  // FEW 2, SCT 4, BKN 7, OVC 8
};

struct MetarReport {
  std::string type = "METAR";         // or SPECI
  std::string station;                // ICAO location indicator
  int day = 0, hour = 0, minute = 0;  // UTC
  bool automatic = false, corrected = false;
  std::optional<MetarWind> wind;  // absent only when the report omits it
  std::optional<MetarVisibility> visibility;
  bool cavok = false;            // ceiling and visibility OK: >= 10 km, no cloud below 5000 ft, no weather
  int runway_visual_ranges = 0;  // Rdd/... groups (read and checked, not used)
  std::vector<MetarWeather> weather;
  std::vector<MetarCloud> clouds;
  std::string sky_clear;  // SKC, CLR, NSC or NCD when the report says so
  std::optional<int> temperature_c, dew_point_c;
  std::optional<double> altimeter_hpa;   // QNH, from Qdddd or Adddd (inHg x 100)
  std::optional<double> altimeter_inhg;  // as reported with A
  bool has_weather(std::string_view phenomenon) const;
};

// Decodes one report. Throws welkin::Error whose `found` names the group, its number and its
// column, and whose `expected` says what belongs there; callers add the file and path.
MetarReport parse_metar(std::string_view text);

const char* cover_code(CloudCover cover);

}  // namespace welkin::weather
