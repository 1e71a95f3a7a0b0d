// One call for everything the sky needs at an instant: sun, moon, their light and eclipses.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "welkin/timeofday/observer.h"
#include "welkin/timeofday/time.h"

namespace welkin::timeofday {

// Knobs of compute_sky.
struct EphemerisOptions {
  // TT - UT in seconds; nullopt takes the Espenak-Meeus polynomial for the date.
  std::optional<double> delta_t_s;
  // Add atmospheric refraction to elevations (from the observer's pressure and temperature).
  bool apply_refraction = true;
  // Linear limb-darkening coefficient for the eclipse flux fraction, [0, 1].
  double limb_darkening_u = 0.6;
};

// The sun as the observer sees it. Angles in degrees; azimuth clockwise from north.
struct SunState {
  double zenith_deg = 0.0;
  double azimuth_deg = 0.0;
  double elevation_deg = 0.0;       // apparent (refracted when enabled)
  double ra_deg = 0.0;              // geocentric apparent
  double dec_deg = 0.0;             // geocentric apparent
  double distance_au = 0.0;         // Earth-sun
  double angular_radius_deg = 0.0;  // topocentric
  double equation_of_time_min = 0.0;
  // Outside the atmosphere on a surface facing the sun, after any eclipse (see
  // SkyState::sun_visible_flux_fraction).
  double illuminance_lux = 0.0;
  double unobscured_illuminance_lux = 0.0;  // the same without the moon in the way
};

// The moon as the observer sees it.
struct MoonState {
  double azimuth_deg = 0.0;
  double elevation_deg = 0.0;  // apparent (refracted when enabled)
  double zenith_deg = 0.0;
  double ra_deg = 0.0;   // geocentric apparent
  double dec_deg = 0.0;  // geocentric apparent
  double topocentric_ra_deg = 0.0;
  double topocentric_dec_deg = 0.0;
  double distance_km = 0.0;         // geocentric
  double angular_radius_deg = 0.0;  // topocentric
  double phase_angle_deg = 0.0;     // 0 full, 180 new
  double illuminated_fraction = 0.0;
  double illuminance_lux = 0.0;  // outside the atmosphere, facing the moon
};

// Everything `welkin sun --json` prints.
struct SkyState {
  double julian_day = 0.0;  // UT
  double delta_t_s = 0.0;   // the value used
  SunState sun;
  MoonState moon;
  // Area of the solar disc not covered by the moon, from topocentric positions.
  double sun_visible_fraction = 1.0;
  // Same, weighted by the limb-darkened brightness: what scales the sun's illuminance.
  double sun_visible_flux_fraction = 1.0;
};

// Sun and moon for `observer` at `time`. Throws std::invalid_argument with a message for an
// invalid observer (see validate), a non-finite Delta-T or limb-darkening coefficient outside
// [0, 1], or a year outside [kSpaFirstYear, kSpaLastYear] (with the default Delta-T, outside
// [kDeltaTFirstYear, kDeltaTLastYear]).
SkyState compute_sky(const Observer& observer, const UtcTime& time,
                     const EphemerisOptions& options = {});

// As compute_sky, but returns nullopt and the message in `error` instead of throwing.
std::optional<SkyState> try_compute_sky(const Observer& observer, const UtcTime& time,
                                        const EphemerisOptions& options = {},
                                        std::string* error = nullptr);

}  // namespace welkin::timeofday
