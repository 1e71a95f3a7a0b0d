#include "welkin/timeofday/sky.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "welkin/timeofday/delta_t.h"
#include "welkin/timeofday/eclipse.h"
#include "welkin/timeofday/illuminance.h"
#include "welkin/timeofday/moon.h"
#include "welkin/timeofday/sun.h"

namespace welkin::timeofday {
namespace {

// Solar radius matching the 959.63" semi-diameter at 1 AU that eclipse canons use, km.
constexpr double kSunRadiusKm = 696000.0;

}  // namespace

SkyState compute_sky(const Observer& observer, const UtcTime& time,
                     const EphemerisOptions& options) {
  if (std::optional<std::string> why = validate(observer)) {
    throw std::invalid_argument("compute_sky: " + *why);
  }
  if (options.delta_t_s && !std::isfinite(*options.delta_t_s)) {
    throw std::invalid_argument("compute_sky: Delta-T is not a finite number");
  }
  if (!std::isfinite(options.limb_darkening_u) || options.limb_darkening_u < 0.0 ||
      options.limb_darkening_u > 1.0) {
    throw std::invalid_argument("compute_sky: limb-darkening coefficient " +
                                std::to_string(options.limb_darkening_u) + " is outside [0, 1]");
  }
  double delta_t = 0.0;
  try {
    delta_t = options.delta_t_s ? *options.delta_t_s : delta_t_espenak_meeus(time.decimal_year());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("compute_sky: " + time.to_iso8601() + ": " + e.what());
  }
  const SolarPosition sun =
      solar_position(observer, time.julian_day(), delta_t, options.apply_refraction);
  const MoonGeocentric moon = moon_geocentric(sun.earth);
  const LunarPhase phase = lunar_phase(moon, sun.geocentric);
  const double moon_radius_geo = angular_radius_deg(kMoonRadiusKm, moon.distance_km);
  const TopocentricPosition moon_topo =
      observe(moon.equatorial, kEarthEquatorialRadiusKm / moon.distance_km, sun.earth, observer,
              RefractionSettings{.enabled = options.apply_refraction,
                                 .body_radius_deg = moon_radius_geo,
                                 .horizon_refraction_deg = 0.5667});

  SkyState sky;
  sky.julian_day = sun.earth.jd_ut;
  sky.delta_t_s = delta_t;

  const double sun_distance_km =
      sun.geocentric.distance_au * kAstronomicalUnitKm * sun.topocentric.distance_ratio;
  const double moon_distance_topo_km = moon.distance_km * moon_topo.distance_ratio;
  sky.sun.zenith_deg = sun.topocentric.zenith_deg;
  sky.sun.azimuth_deg = sun.topocentric.azimuth_deg;
  sky.sun.elevation_deg = sun.topocentric.elevation_deg;
  sky.sun.ra_deg = sun.geocentric.equatorial.ra_deg;
  sky.sun.dec_deg = sun.geocentric.equatorial.dec_deg;
  sky.sun.distance_au = sun.geocentric.distance_au;
  sky.sun.angular_radius_deg = angular_radius_deg(kSunRadiusKm, sun_distance_km);
  sky.sun.equation_of_time_min = sun.geocentric.equation_of_time_min;

  sky.moon.azimuth_deg = moon_topo.azimuth_deg;
  sky.moon.elevation_deg = moon_topo.elevation_deg;
  sky.moon.zenith_deg = moon_topo.zenith_deg;
  sky.moon.ra_deg = moon.equatorial.ra_deg;
  sky.moon.dec_deg = moon.equatorial.dec_deg;
  sky.moon.topocentric_ra_deg = moon_topo.equatorial.ra_deg;
  sky.moon.topocentric_dec_deg = moon_topo.equatorial.dec_deg;
  sky.moon.distance_km = moon.distance_km;
  sky.moon.angular_radius_deg = angular_radius_deg(kMoonRadiusKm, moon_distance_topo_km);
  sky.moon.phase_angle_deg = phase.phase_angle_deg;
  sky.moon.illuminated_fraction = phase.illuminated_fraction;
  sky.moon.illuminance_lux =
      moon_illuminance_lux(phase.phase_angle_deg, moon.distance_km, sun.geocentric.distance_au);

  // Eclipses from where the observer stands: the moon's parallax reaches a degree.
  const double separation =
      angular_separation_deg(sun.topocentric.equatorial, moon_topo.equatorial);
  sky.sun_visible_fraction =
      sun_visible_fraction(sky.sun.angular_radius_deg, sky.moon.angular_radius_deg, separation);
  sky.sun_visible_flux_fraction =
      sun_visible_flux_fraction(sky.sun.angular_radius_deg, sky.moon.angular_radius_deg, separation,
                                options.limb_darkening_u);
  sky.sun.unobscured_illuminance_lux = sun_illuminance_lux(sun.geocentric.distance_au);
  sky.sun.illuminance_lux = sky.sun.unobscured_illuminance_lux * sky.sun_visible_flux_fraction;
  return sky;
}

std::optional<SkyState> try_compute_sky(const Observer& observer, const UtcTime& time,
                                        const EphemerisOptions& options, std::string* error) {
  try {
    return compute_sky(observer, time, options);
  } catch (const std::invalid_argument& e) {
    if (error != nullptr) *error = e.what();
    return std::nullopt;
  }
}

}  // namespace welkin::timeofday
