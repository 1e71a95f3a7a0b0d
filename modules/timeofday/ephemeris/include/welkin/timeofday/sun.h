// The sun by the NREL Solar Position Algorithm (Reda & Andreas 2004, NREL/TP-560-34302):
// +/-0.0003 degrees from -2000 to 6000, given an accurate Delta-T.
#pragma once

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/earth_orientation.h"
#include "welkin/timeofday/observer.h"

namespace welkin::timeofday {

// Years the SPA paper states its accuracy for.
inline constexpr double kSpaFirstYear = -2000.0;
inline constexpr double kSpaLastYear = 6000.0;

// Earth's heliocentric longitude in degrees [0, 360) at `jme` Julian ephemeris millennia since
// J2000.0, from the truncated VSOP87 series of SPA Table A4.2 (eqs. 9-11).
double heliocentric_longitude_deg(double jme);

// Earth's heliocentric latitude in degrees (SPA eq. 12).
double heliocentric_latitude_deg(double jme);

// Earth-sun distance in astronomical units (SPA eq. 13 with the R tables).
double earth_sun_distance_au(double jme);

// The observer-independent half of SPA: where the sun is on the celestial sphere.
struct SunGeocentric {
  double heliocentric_longitude_deg = 0.0;  // L
  double heliocentric_latitude_deg = 0.0;   // B
  double distance_au = 0.0;                 // R
  double geocentric_longitude_deg = 0.0;    // Theta
  double geocentric_latitude_deg = 0.0;     // beta
  double aberration_deg = 0.0;              // Delta-tau
  double apparent_longitude_deg = 0.0;      // lambda
  Equatorial equatorial;                    // geocentric apparent alpha, delta
  double equation_of_time_min = 0.0;        // E, apparent minus mean solar time, (-20, 20]
};

// SPA steps 3.2-3.9 and the equation of time (appendix A.1) for the given Earth orientation.
SunGeocentric sun_geocentric(const EarthOrientation& earth);

// Sine of the sun's equatorial horizontal parallax, 8.794" at 1 AU (SPA eq. 33).
double sun_sin_parallax(double distance_au);

// Refraction settings SPA uses for the sun: its 0.26667 degree radius and 0.5667 degree refraction
// at the horizon.
RefractionSettings sun_refraction_settings(bool enabled = true);

// The complete SPA result for an observer.
struct SolarPosition {
  EarthOrientation earth;
  SunGeocentric geocentric;
  TopocentricPosition topocentric;
};

// Runs SPA for `observer` at Julian Day `jd_ut` with Delta-T `delta_t_s`. Throws
// std::invalid_argument for an invalid observer, a non-finite input or a date outside
// [kSpaFirstYear, kSpaLastYear].
SolarPosition solar_position(const Observer& observer, double jd_ut, double delta_t_s,
                             bool apply_refraction = true);

}  // namespace welkin::timeofday
