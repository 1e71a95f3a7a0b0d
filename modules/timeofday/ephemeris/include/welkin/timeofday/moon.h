// The moon by Meeus, Astronomical Algorithms 2nd ed.: position from the truncated ELP-2000/82
// series of chapter 47 (about 10" in longitude, 4" in latitude), phase from chapter 48.
#pragma once

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/earth_orientation.h"
#include "welkin/timeofday/sun.h"

namespace welkin::timeofday {

// Earth's equatorial radius as Meeus uses it for parallax, km.
inline constexpr double kEarthEquatorialRadiusKm = 6378.14;
// Mean lunar radius (IAU), km; sets the moon's angular size.
inline constexpr double kMoonRadiusKm = 1737.4;
// Mean Earth-moon distance, km, the reference of the lunar illuminance law.
inline constexpr double kMoonMeanDistanceKm = 384400.0;
// Astronomical unit, km (IAU 2012).
inline constexpr double kAstronomicalUnitKm = 149597870.7;

// The moon's geocentric position, degrees and km.
struct MoonGeocentric {
  double mean_longitude_deg = 0.0;       // L', reduced to [0, 360)
  double longitude_deg = 0.0;            // lambda, geometric, mean equinox of date
  double latitude_deg = 0.0;             // beta
  double distance_km = 0.0;              // Delta, centre to centre
  double horizontal_parallax_deg = 0.0;  // pi, asin(Earth radius / Delta)
  double apparent_longitude_deg = 0.0;   // lambda + Delta-psi
  Equatorial equatorial;                 // apparent alpha, delta
};

// Meeus ch. 47 at the Julian Ephemeris Day of `earth`, with its nutation and true obliquity.
MoonGeocentric moon_geocentric(const EarthOrientation& earth);

// How much of the moon is lit, from Earth's centre (Meeus ch. 48).
struct LunarPhase {
  double elongation_deg = 0.0;        // psi, sun-earth-moon angle
  double phase_angle_deg = 0.0;       // i, sun-moon-earth angle: 0 full, 180 new
  double illuminated_fraction = 0.0;  // k = (1 + cos i) / 2
};

// Phase from the geocentric moon and sun (Meeus eqs. 48.2, 48.3, 48.1).
LunarPhase lunar_phase(const MoonGeocentric& moon, const SunGeocentric& sun);

// Angular radius in degrees of a body of radius `radius_km` seen from `distance_km`.
double angular_radius_deg(double radius_km, double distance_km);

}  // namespace welkin::timeofday
