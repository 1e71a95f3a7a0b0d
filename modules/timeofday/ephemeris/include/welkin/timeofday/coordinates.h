// Angle helpers and the coordinate conversions that sun, moon and renderer share.
#pragma once

#include <array>

namespace welkin::timeofday {

inline constexpr double kPi = 3.141592653589793238462643383279502884;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

// `degrees` reduced to [0, 360).
double normalize_degrees(double degrees);

// `degrees` reduced to (-180, 180].
double normalize_degrees_signed(double degrees);

// Right ascension and declination, degrees, RA in [0, 360).
struct Equatorial {
  double ra_deg = 0.0;
  double dec_deg = 0.0;
};

// Ecliptic longitude/latitude to equatorial coordinates for obliquity `obliquity_deg`
// (SPA eqs. 38-39; Meeus eqs. 13.3-13.4).
Equatorial ecliptic_to_equatorial(double longitude_deg, double latitude_deg, double obliquity_deg);

// Great-circle angle between two equatorial directions, degrees. Uses atan2(|a x b|, a . b), which
// stays accurate at arc-second separations where the arccos form loses digits (eclipses need it).
double angular_separation_deg(const Equatorial& a, const Equatorial& b);

// Unit vector {east, north, up} in a local East-North-Up frame for an azimuth measured clockwise
// from north and an elevation above the horizon, both degrees.
std::array<double, 3> enu_direction(double azimuth_deg, double elevation_deg);

}  // namespace welkin::timeofday
