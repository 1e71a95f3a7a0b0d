// Writes what a report means into the scene's components, through their public types; a component
// the scene lacks is added with the defaults its module registered (the host's type description).
#include "apply_report.h"

#include <chrono>

#include "welkin/atmosphere/components.h"
#include "welkin/clouds/components.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/json_fields.h"
#include "welkin/timeofday/components.h"
#include "welkin/weather/components.h"
#include "welkin/weather/sky_from_metar.h"
#include "welkin/weather/station_table.h"

namespace welkin::weather {

namespace {

// What was last applied, so that a report is applied once, not every frame.
struct AppliedReport {
  static constexpr std::string_view kTypeName = "weather.AppliedReport";
  std::string key;
  bool added_clock = false;  // the scene had no time of day: the module added it
};

template <class T>
const TypeDesc& registered_type(World& world) {
  const ComponentInfo* info = world.modules().component(type_id<T>());
  if (!info) throw Error("weather: the module providing " + std::string(T::kTypeName) + " is not loaded");
  return *info->type;
}

// The scene's component T (its first), or one added to `owner`.
template <class T>
T& scene_component(World& world, Entity owner, bool* added = nullptr) {
  Registry& reg = world.registry();
  Entity e = reg.first<T>();
  if (added) *added = e.is_null();
  if (e.is_null()) return *static_cast<T*>(reg.emplace(owner, registered_type<T>(world)));
  return *reg.get<T>(e);
}

void set_clock_and_place(World& world, Entity owner, const Report& report, const SkyFromReport& sky,
                         const std::string& station, const std::filesystem::path& table) {
  AppliedReport& applied = world.resource<AppliedReport>();
  bool added = false;
  auto& tod = scene_component<timeofday::TimeOfDay>(world, owner, &added);
  applied.added_clock = applied.added_clock || added;
  if (report.year) tod.year = report.year;
  if (report.month) tod.month = report.month;
  using namespace std::chrono;
  if (!year_month_day(year(tod.year), month(unsigned(tod.month)), day(unsigned(sky.day))).ok())
    throw Error(ErrorInfo{.path = "/metar",
                          .expected = "a day of " + std::to_string(tod.year) + "-" +
                                      std::to_string(tod.month) + " (set /year and /month)",
                          .found = "day " + std::to_string(sky.day)});
  tod.day = sky.day;
  tod.local_time_h = sky.utc_time_h;  // a report's time is UTC: the scene's clock runs on UTC
  tod.utc_offset_h = 0.0;
  bool use_station =
      report.place == ReportPlace::station || (report.place == ReportPlace::automatic && applied.added_clock);
  if (!use_station) return;
  std::optional<Station> found = find_station(table.string(), station);
  if (!found)
    throw Error(ErrorInfo{.file = table.string(),
                          .path = "/metar",
                          .expected = "a station of the table (or weather.Report place 'scene' and a "
                                      "timeofday.TimeOfDay with the scene's place)",
                          .found = "station " + station + ", which it does not list"});
  tod.latitude_deg = found->latitude_deg;
  tod.longitude_deg = found->longitude_deg;
  check_object(registered_type<timeofday::TimeOfDay>(world), &tod);
}

void set_clouds(World& world, Entity owner, const SkyFromReport& sky) {
  Registry& reg = world.registry();
  if (sky.layers.empty() && reg.first<clouds::VolumetricClouds>().is_null()) return;  // clear, and no clouds
  auto& vc = scene_component<clouds::VolumetricClouds>(world, owner);
  vc.layers = sky.layers;
  vc.coverage = 1.0f;  // the layers' coverage is the report's
  vc.wind_mps = sky.wind_mps;
  check_object(registered_type<clouds::VolumetricClouds>(world), &vc);
}

void set_haze(World& world, Entity owner, const SkyFromReport& sky) {
  if (!sky.visibility_m) return;
  auto& air = scene_component<atmosphere::Atmosphere>(world, owner);
  // Keep the scene's aerosol albedo; scale its extinction to the visibility.
  float albedo = air.mie_extinction.y > 0.0f ? air.mie_scattering.y / air.mie_extinction.y : 0.9f;
  float extinction = float(haze_extinction_per_km(*sky.visibility_m, air.rayleigh_scattering.y));
  air.mie_extinction = glm::vec3(extinction);
  air.mie_scattering = glm::vec3(extinction * albedo);
  check_object(registered_type<atmosphere::Atmosphere>(world), &air);
}

}  // namespace

void apply_report_system(SystemContext& ctx, const std::filesystem::path& station_table) {
  World& world = ctx.world;
  Entity owner = world.registry().first<Report>();
  if (owner.is_null()) return;
  const Report report = *world.registry().get<Report>(owner);
  std::string key = report.metar + "|" + std::to_string(report.year) + "|" + std::to_string(report.month) +
                    "|" + std::to_string(int(report.place));
  AppliedReport& applied = world.resource<AppliedReport>();
  if (report.metar.empty() || key == applied.key) return;
  try {
    MetarReport metar = parse_metar(report.metar);
    SkyFromReport sky = sky_from_metar(metar);
    set_clock_and_place(world, owner, report, sky, metar.station, station_table);
    set_clouds(world, owner, sky);
    set_haze(world, owner, sky);
  } catch (const Error& e) {
    if (e.info().path.rfind("/", 0) == 0 || e.info().path.empty())
      throw e.with_path_prefix(std::string(Report::kTypeName));
    throw;
  }
  world.resource<AppliedReport>().key = key;
}

}  // namespace welkin::weather
