// The time-of-day system: advances the clock and writes the sun, the moon, the clock and the origin's
// place into the world's shared state (welkin/scene/shared_state.h).
#include <cmath>
#include <stdexcept>

#include "time_of_day_system.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/shared_state.h"
#include "welkin/timeofday/earth_orientation.h"
#include "welkin/timeofday/sky.h"

namespace welkin::timeofday {

namespace {

// Publishes where the sun and the moon stand, the clock and the origin's place into the world's
// shared state; the modules that draw lights (or the runtime's default light) follow from there.
void publish(World& world, const TimeOfDay& tod, const SkyState& sky) {
  LightSources& lights = world.resource<LightSources>();
  lights.ephemeris.sun = {.present = true,
                          .azimuth_deg = sky.sun.azimuth_deg,
                          .elevation_deg = sky.sun.elevation_deg,
                          .illuminance_lux = sky.sun.unobscured_illuminance_lux,
                          .angular_radius_deg = sky.sun.angular_radius_deg,
                          .visible_fraction = sky.sun_visible_flux_fraction};
  lights.ephemeris.moon = {.present = true,
                           .azimuth_deg = sky.moon.azimuth_deg,
                           .elevation_deg = sky.moon.elevation_deg,
                           .illuminance_lux = sky.moon.illuminance_lux,
                           .angular_radius_deg = sky.moon.angular_radius_deg,
                           .illuminated_fraction = sky.moon.illuminated_fraction};
  SceneTime& time = world.resource<SceneTime>();
  time.present = true;
  time.local_time_h = tod.local_time_h;
  time.julian_day = sky.julian_day;
  // The stars turn with the local (mean) sidereal time.
  time.local_sidereal_time_deg =
      std::fmod(mean_sidereal_time_deg(sky.julian_day) + tod.longitude_deg + 720.0, 360.0);
  world.resource<PlanetFrame>().origin = GeodeticPlace{
      .latitude_deg = tod.latitude_deg, .longitude_deg = tod.longitude_deg, .elevation_m = tod.elevation_m};
}

}  // namespace

UtcTime utc_of(const TimeOfDay& tod) {
  double h = tod.local_time_h;
  int hour = int(std::floor(h));
  double minutes = (h - hour) * 60.0;
  int minute = int(std::floor(minutes));
  double second = (minutes - minute) * 60.0;
  try {
    return UtcTime::from_civil(tod.year, tod.month, tod.day, hour, minute, std::min(second, 59.999999),
                               int(std::lround(tod.utc_offset_h * 60.0)));
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorInfo{.path = std::string(TimeOfDay::kTypeName), .message = e.what()});
  }
}

void set_local_time(TimeOfDay& tod, const UtcTime& utc) {
  CivilDateTime c = utc.plus_seconds(tod.utc_offset_h * 3600.0).civil();
  tod.year = int(c.year);
  tod.month = c.month;
  tod.day = c.day;
  tod.local_time_h = c.hour + c.minute / 60.0 + c.second / 3600.0;
}

SkyState sky_of(const TimeOfDay& tod) {
  Observer obs{.latitude_deg = tod.latitude_deg,
               .longitude_deg = tod.longitude_deg,
               .elevation_m = tod.elevation_m,
               .pressure_mbar = tod.pressure_mbar,
               .temperature_c = tod.temperature_c};
  EphemerisOptions opt{.apply_refraction = tod.refraction};
  if (tod.delta_t_mode == DeltaTMode::manual) opt.delta_t_s = tod.delta_t_s;
  std::string err;
  auto sky = try_compute_sky(obs, utc_of(tod), opt, &err);
  if (!sky) throw Error(ErrorInfo{.path = std::string(TimeOfDay::kTypeName), .message = err});
  return *sky;
}

void time_of_day_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  bool sequenced = !reg.first<SequencePlayer>().is_null();
  reg.each<TimeOfDay>([&](Entity, TimeOfDay& tod) {
    // A sequence owns time when present (scrubbing must equal playing), so the clock only runs alone.
    if (!sequenced && tod.time_scale != 0.0f && sc.frame.dt_s > 0.0)
      set_local_time(tod, utc_of(tod).plus_seconds(sc.frame.dt_s * tod.time_scale));
    publish(sc.world, tod, sky_of(tod));
  });
}

}  // namespace welkin::timeofday
