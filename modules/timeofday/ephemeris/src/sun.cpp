#include "welkin/timeofday/sun.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sun_periodic_terms.h"
#include "welkin/timeofday/time.h"

namespace welkin::timeofday {
namespace {

// Sums a family of series L0 + L1 t + L2 t^2 + ... (SPA eqs. 9-11), in units of 1e-8.
template <std::size_t N>
double sum_series(const detail::PeriodicSeries (&series)[N], double jme) {
  double total = 0.0;
  double power = 1.0;
  for (const detail::PeriodicSeries& s : series) {
    double sum = 0.0;
    for (const detail::PeriodicTerm& term : s) sum += term.a * std::cos(term.b + term.c * jme);
    total += sum * power;
    power *= jme;
  }
  return total / 1.0e8;
}

// The sun's mean longitude in degrees (SPA eq. A2), for the equation of time.
double sun_mean_longitude_deg(double jme) {
  return 280.4664567 +
         jme * (360007.6982779 +
                jme * (0.03032028 +
                       jme * (1.0 / 49931.0 + jme * (-1.0 / 15300.0 + jme * (-1.0 / 2000000.0)))));
}

// Julian Day of January 1, 0h, of a (whole) proleptic Gregorian year.
double year_start_julian_day(double year) {
  return kUnixEpochJulianDay +
         static_cast<double>(days_from_civil(static_cast<std::int64_t>(year), 1, 1));
}

}  // namespace

double heliocentric_longitude_deg(double jme) {
  return normalize_degrees(sum_series(detail::kEarthLongitude, jme) * kRadToDeg);
}

double heliocentric_latitude_deg(double jme) {
  return sum_series(detail::kEarthLatitude, jme) * kRadToDeg;
}

double earth_sun_distance_au(double jme) { return sum_series(detail::kEarthRadius, jme); }

SunGeocentric sun_geocentric(const EarthOrientation& earth) {
  SunGeocentric s;
  s.heliocentric_longitude_deg = heliocentric_longitude_deg(earth.jme);
  s.heliocentric_latitude_deg = heliocentric_latitude_deg(earth.jme);
  s.distance_au = earth_sun_distance_au(earth.jme);
  // Seen from Earth the sun sits opposite Earth as seen from the sun (SPA eqs. 14-15).
  s.geocentric_longitude_deg = normalize_degrees(s.heliocentric_longitude_deg + 180.0);
  s.geocentric_latitude_deg = -s.heliocentric_latitude_deg;
  // Annual aberration: light travel time shifts the sun back by ~20.5" (SPA eq. 28).
  s.aberration_deg = -20.4898 / (3600.0 * s.distance_au);
  s.apparent_longitude_deg = normalize_degrees(s.geocentric_longitude_deg +
                                               earth.nutation.longitude_deg + s.aberration_deg);
  s.equatorial = ecliptic_to_equatorial(s.apparent_longitude_deg, s.geocentric_latitude_deg,
                                        earth.true_obliquity_deg);
  // SPA eq. A1: mean minus apparent right ascension, with the equation of the equinoxes; wrapping
  // to (-180, 180] degrees keeps it within the +/-20 minutes SPA's limit step allows.
  const double e_deg =
      sun_mean_longitude_deg(earth.jme) - 0.0057183 - s.equatorial.ra_deg +
      earth.nutation.longitude_deg * std::cos(earth.true_obliquity_deg * kDegToRad);
  s.equation_of_time_min = normalize_degrees_signed(e_deg) * 4.0;
  return s;
}

double sun_sin_parallax(double distance_au) {
  return std::sin(8.794 / (3600.0 * distance_au) * kDegToRad);
}

RefractionSettings sun_refraction_settings(bool enabled) {
  return RefractionSettings{
      .enabled = enabled, .body_radius_deg = 0.26667, .horizon_refraction_deg = 0.5667};
}

SolarPosition solar_position(const Observer& observer, double jd_ut, double delta_t_s,
                             bool apply_refraction) {
  if (std::optional<std::string> why = validate(observer)) {
    throw std::invalid_argument("solar_position: " + *why);
  }
  if (!std::isfinite(jd_ut))
    throw std::invalid_argument("solar_position: Julian Day is not finite");
  if (!std::isfinite(delta_t_s))
    throw std::invalid_argument("solar_position: Delta-T is not finite");
  const double first = year_start_julian_day(kSpaFirstYear);
  const double end = year_start_julian_day(kSpaLastYear + 1.0);
  if (jd_ut < first || jd_ut >= end) {
    throw std::invalid_argument("solar_position: Julian Day " + std::to_string(jd_ut) +
                                " is outside the years -2000..6000 that SPA supports");
  }
  SolarPosition p;
  p.earth = earth_orientation(jd_ut, delta_t_s);
  p.geocentric = sun_geocentric(p.earth);
  p.topocentric = observe(p.geocentric.equatorial, sun_sin_parallax(p.geocentric.distance_au),
                          p.earth, observer, sun_refraction_settings(apply_refraction));
  return p;
}

}  // namespace welkin::timeofday
