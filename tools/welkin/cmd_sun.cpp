// welkin sun --lat D --lon D --utc ISO8601 [--elevation-m M] [--pressure-mbar P] [--temperature-c T]
//            [--delta-t S] [--no-refraction] [--json]
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "commands.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/timeofday/sky.h"

namespace welkin::cli {

namespace {

struct SunOptions {
  double lat = NAN, lon = NAN, elevation_m = 0, pressure_mbar = 1013.25, temperature_c = 15;
  std::optional<double> delta_t;
  std::string utc;
  bool no_refraction = false;
  bool json = false;
};

int run_sun(const SunOptions& o) {
  using namespace welkin::timeofday;
  Observer obs{.latitude_deg = o.lat, .longitude_deg = o.lon, .elevation_m = o.elevation_m,
               .pressure_mbar = o.pressure_mbar, .temperature_c = o.temperature_c};
  std::string err;
  auto t = UtcTime::try_parse(o.utc, &err);
  if (!t) throw Error(ErrorInfo{.path = "--utc", .expected = "an ISO 8601 date-time with offset, e.g. 2024-04-08T18:17:16Z",
                                .found = "'" + o.utc + "'", .message = err});
  EphemerisOptions opt{.delta_t_s = o.delta_t, .apply_refraction = !o.no_refraction};
  auto sky = try_compute_sky(obs, *t, opt, &err);
  if (!sky) throw Error(ErrorInfo{.message = err});
  const SunState& s = sky->sun;
  const MoonState& m = sky->moon;
  if (o.json) {
    nlohmann::json j{
        {"sun", {{"zenith_deg", s.zenith_deg}, {"azimuth_deg", s.azimuth_deg}, {"elevation_deg", s.elevation_deg},
                 {"ra_deg", s.ra_deg}, {"dec_deg", s.dec_deg}, {"distance_au", s.distance_au},
                 {"angular_radius_deg", s.angular_radius_deg}, {"illuminance_lux", s.illuminance_lux},
                 {"equation_of_time_min", s.equation_of_time_min}}},
        {"moon", {{"azimuth_deg", m.azimuth_deg}, {"elevation_deg", m.elevation_deg}, {"ra_deg", m.ra_deg},
                  {"dec_deg", m.dec_deg}, {"distance_km", m.distance_km}, {"illuminated_fraction", m.illuminated_fraction},
                  {"phase_angle_deg", m.phase_angle_deg}, {"angular_radius_deg", m.angular_radius_deg},
                  {"illuminance_lux", m.illuminance_lux}}},
        {"sun_visible_fraction", sky->sun_visible_fraction},
        {"julian_day", sky->julian_day},
        {"delta_t_s", sky->delta_t_s}};
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf("time            %s  (JD %.6f, delta-T %.2f s)\n", t->to_iso8601().c_str(), sky->julian_day, sky->delta_t_s);
  std::printf("observer        lat %.6f  lon %.6f  elevation %.1f m\n", o.lat, o.lon, o.elevation_m);
  std::printf("sun             zenith %.5f deg  azimuth %.5f deg  elevation %.5f deg\n", s.zenith_deg, s.azimuth_deg, s.elevation_deg);
  std::printf("                illuminance %.0f lx outside the atmosphere\n", s.illuminance_lux);
  std::printf("moon            azimuth %.5f deg  elevation %.5f deg\n", m.azimuth_deg, m.elevation_deg);
  std::printf("                RA %.5f deg  dec %.5f deg (geocentric apparent)  distance %.1f km\n", m.ra_deg, m.dec_deg, m.distance_km);
  std::printf("                illuminated %.4f  phase angle %.3f deg  %.4f lx\n", m.illuminated_fraction, m.phase_angle_deg, m.illuminance_lux);
  std::printf("eclipse         sun visible fraction %.6f\n", sky->sun_visible_fraction);
  return kOk;
}

}  // namespace

void add_sun_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SunOptions>();
  CLI::App* cmd = app.add_subcommand("sun", "Sun and moon positions (NREL SPA, Meeus ch. 47) and eclipse visibility");
  cmd->add_option("--lat", o->lat, "Geodetic latitude, degrees north")->required();
  cmd->add_option("--lon", o->lon, "Longitude, degrees east")->required();
  cmd->add_option("--utc", o->utc, "Date-time, ISO 8601 with offset (2003-10-17T19:30:30Z)")->required();
  cmd->add_option("--elevation-m", o->elevation_m, "Observer elevation above sea level")->capture_default_str();
  cmd->add_option("--pressure-mbar", o->pressure_mbar, "Pressure, for refraction")->capture_default_str();
  cmd->add_option("--temperature-c", o->temperature_c, "Temperature, for refraction")->capture_default_str();
  cmd->add_option("--delta-t", o->delta_t, "TT - UT in seconds (default: Espenak-Meeus polynomial)");
  cmd->add_flag("--no-refraction", o->no_refraction, "Report geometric (unrefracted) elevations");
  cmd->add_flag("--json", o->json, "Machine-readable output");
  cmd->callback([o, &exit_code] { exit_code = run_sun(*o); });
}

}  // namespace welkin::cli
