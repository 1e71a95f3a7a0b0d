// The time-of-day system: advances the clock and writes the sun, the moon and the stars into the scene.
#include <cmath>
#include <stdexcept>

#include "time_of_day_system.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/field_path.h"
#include "welkin/timeofday/earth_orientation.h"
#include "welkin/timeofday/sky.h"

namespace welkin::timeofday {

namespace {

// Sets a field of the first entity with `component`, if the scene has one. Lights belong to other
// modules (or the core), so they are reached by name through reflection, not by type.
void set_if_present(World& world, std::string_view component, std::string_view field, double value) {
  const ComponentInfo* info = world.modules().component(component);
  if (!info) return;
  const ComponentPool* pool = world.registry().pool(info->type->id);
  if (!pool || pool->empty()) return;
  void* object = world.registry().get(pool->entities()[0], info->type->id);
  resolve_field(*info->type, object, field).set_scalar(value);
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
  Observer obs{.latitude_deg = tod.latitude_deg, .longitude_deg = tod.longitude_deg, .elevation_m = tod.elevation_m,
               .pressure_mbar = tod.pressure_mbar, .temperature_c = tod.temperature_c};
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
    SkyState sky = sky_of(tod);
    World& w = sc.world;
    set_if_present(w, "atmosphere.Sun", "azimuth_deg", sky.sun.azimuth_deg);
    set_if_present(w, "atmosphere.Sun", "elevation_deg", sky.sun.elevation_deg);
    set_if_present(w, "atmosphere.Sun", "illuminance_lux", sky.sun.unobscured_illuminance_lux);
    set_if_present(w, "atmosphere.Sun", "angular_radius_deg", sky.sun.angular_radius_deg);
    set_if_present(w, "atmosphere.Sun", "visible_fraction", sky.sun_visible_flux_fraction);
    set_if_present(w, "atmosphere.Moon", "azimuth_deg", sky.moon.azimuth_deg);
    set_if_present(w, "atmosphere.Moon", "elevation_deg", sky.moon.elevation_deg);
    set_if_present(w, "atmosphere.Moon", "illuminance_lux", sky.moon.illuminance_lux);
    set_if_present(w, "atmosphere.Moon", "angular_radius_deg", sky.moon.angular_radius_deg);
    set_if_present(w, "atmosphere.Moon", "illuminated_fraction", sky.moon.illuminated_fraction);
    // The stars turn with the local (mean) sidereal time.
    const double lst = std::fmod(mean_sidereal_time_deg(sky.julian_day) + tod.longitude_deg + 720.0, 360.0);
    set_if_present(w, "atmosphere.Stars", "local_sidereal_time_deg", lst);
    set_if_present(w, "atmosphere.Stars", "latitude_deg", tod.latitude_deg);
    // Without an atmosphere, the built-in light follows the sun (dimmed by eclipses, off at night).
    set_if_present(w, "core.DirectionalLight", "azimuth_deg", sky.sun.azimuth_deg);
    set_if_present(w, "core.DirectionalLight", "elevation_deg", sky.sun.elevation_deg);
    set_if_present(w, "core.DirectionalLight", "illuminance_lux",
                   sky.sun.elevation_deg > 0 ? sky.sun.illuminance_lux * std::sin(sky.sun.elevation_deg * M_PI / 180.0) : 0.0);
  });
}

}  // namespace welkin::timeofday
