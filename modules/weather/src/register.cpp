#include "apply_report.h"
#include "welkin/core/error.h"
#include "welkin/core/module.h"
#include "welkin/weather/components.h"
#include "welkin/weather/metar.h"

namespace welkin::weather {

void describe(TypeBuilder<Report>& t) {
  t.tooltip(
      "A METAR report that sets the sky: cloud layers, haze, the clouds' drift, the clock and the place");
  t.field("metar", &Report::metar).tooltip("e.g. KSFO 271756Z 28012KT 10SM FEW008 SCT025 BKN250 18/12 A3001");
  t.field("year", &Report::year).range(0, 2100).tooltip("The report's year; 0 keeps the time of day's");
  t.field("month", &Report::month).range(0, 12).tooltip("The report's month; 0 keeps the time of day's");
  t.field("place", &Report::place)
      .values({{"automatic", 0}, {"station", 1}, {"scene", 2}})
      .tooltip("automatic: the scene's place when it has a time of day, else the station's");
  // A malformed report is refused where it is written (scene file, --metar, the editor).
  t.validate([](const Report& r) {
    if (r.year != 0 && r.year < 1900)
      throw Error(ErrorInfo{.path = "/year", .expected = "0 or 1900-2100", .found = std::to_string(r.year)});
    try {
      if (!r.metar.empty()) parse_metar(r.metar);
    } catch (const Error& e) {
      throw e.with_path_prefix("/metar");
    }
  });
}

}  // namespace welkin::weather

namespace welkin::modules {
void register_weather(ModuleContext& ctx) {
  using namespace welkin::weather;
  ctx.component<Report>();
  std::filesystem::path table = ctx.manifest().data_dir / "data" / "stations.csv";
  // Before the time of day computes the sun from the clock the report sets.
  ctx.system({.name = "weather.apply_report",
              .stage = Stage::simulate,
              .before = {"timeofday.sun_and_moon"},
              .writes = {type_id<Report>()},
              .run = [table](SystemContext& sc) { apply_report_system(sc, table); }});
}
}  // namespace welkin::modules
