#include "welkin/timeofday/earth_orientation.h"

#include <cmath>

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/time.h"

namespace welkin::timeofday {
namespace {

// One row of the IAU 1980 nutation series: multiples of (D, M, M', F, Omega), then the sine
// coefficients (a + b T) for Delta-psi and cosine coefficients (c + d T) for Delta-epsilon, in
// units of 0.0001 arc-second (SPA Table A4.3; Meeus Table 22.A).
struct NutationTerm {
  signed char y[5];
  double a, b, c, d;
};

constexpr NutationTerm kNutationTerms[63] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9},
    {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},
    {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},
    {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},
    {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},
    {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
    {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
    {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
    {{0, 0, -1, 2, 2}, 123, 0, -53, 0},
    {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},
    {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
    {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
    {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
    {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},
    {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0},
    {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
    {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
    {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
    {{0, 0, 0, 2, 0}, 26, 0, 0, 0},
    {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0},
    {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
    {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
    {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
    {{0, 1, 0, 0, 1}, -15, 0, 9, 0},
    {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0},
    {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
    {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
    {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
    {{0, 1, 0, 2, 2}, 7, 0, -3, 0},
    {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0},
    {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
    {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
    {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
    {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},
    {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0},
    {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
    {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
    {{0, 0, 2, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},
    {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
    {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
    {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
    {{1, 0, 0, 0, 0}, -4, 0, 0, 0},
    {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0},
    {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
    {{2, -1, -1, 2, 2}, -3, 0, 0, 0},
    {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0},
};

}  // namespace

LunisolarArguments lunisolar_arguments(double t) {
  // SPA eqs. 15-19 (Meeus ch. 22): cubic polynomials in Julian ephemeris centuries.
  LunisolarArguments x;
  x.moon_mean_elongation_deg = 297.85036 + t * (445267.111480 + t * (-0.0019142 + t / 189474.0));
  x.sun_mean_anomaly_deg = 357.52772 + t * (35999.050340 + t * (-0.0001603 - t / 300000.0));
  x.moon_mean_anomaly_deg = 134.96298 + t * (477198.867398 + t * (0.0086972 + t / 56250.0));
  x.moon_argument_of_latitude_deg =
      93.27191 + t * (483202.017538 + t * (-0.0036825 + t / 327270.0));
  x.moon_ascending_node_deg = 125.04452 + t * (-1934.136261 + t * (0.0020708 + t / 450000.0));
  return x;
}

Nutation nutation(double jce) {
  const LunisolarArguments x = lunisolar_arguments(jce);
  const double args[5] = {x.moon_mean_elongation_deg, x.sun_mean_anomaly_deg,
                          x.moon_mean_anomaly_deg, x.moon_argument_of_latitude_deg,
                          x.moon_ascending_node_deg};
  double sum_psi = 0.0;
  double sum_eps = 0.0;
  for (const NutationTerm& term : kNutationTerms) {
    double angle = 0.0;
    for (int k = 0; k < 5; ++k) angle += term.y[k] * args[k];
    angle *= kDegToRad;
    sum_psi += (term.a + term.b * jce) * std::sin(angle);
    sum_eps += (term.c + term.d * jce) * std::cos(angle);
  }
  // Coefficients are in 0.0001", so 36 000 000 units per degree.
  return {sum_psi / 36000000.0, sum_eps / 36000000.0};
}

double mean_obliquity_arcsec(double jme) {
  static constexpr double c[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                 -39.05,    7.12,     27.87, 5.79,    2.45};
  const double u = jme / 10.0;
  double sum = 0.0;
  for (int i = 10; i >= 0; --i) sum = sum * u + c[i];
  return sum;
}

double mean_sidereal_time_deg(double jd_ut) {
  const double days = jd_ut - kJ2000JulianDay;
  const double t = days / kDaysPerJulianCentury;
  return normalize_degrees(280.46061837 + 360.98564736629 * days +
                           t * t * (0.000387933 - t / 38710000.0));
}

EarthOrientation earth_orientation(double jd_ut, double delta_t_s) {
  EarthOrientation e;
  e.jd_ut = jd_ut;
  e.delta_t_s = delta_t_s;
  e.jde = julian_ephemeris_day(jd_ut, delta_t_s);
  e.jc = julian_century(jd_ut);
  e.jce = julian_century(e.jde);
  e.jme = e.jce / 10.0;
  e.arguments = lunisolar_arguments(e.jce);
  e.nutation = nutation(e.jce);
  e.mean_obliquity_deg = mean_obliquity_arcsec(e.jme) / 3600.0;
  e.true_obliquity_deg = e.mean_obliquity_deg + e.nutation.obliquity_deg;
  e.mean_sidereal_time_deg = mean_sidereal_time_deg(jd_ut);
  // The equation of the equinoxes turns mean into apparent sidereal time (SPA eq. 31).
  e.apparent_sidereal_time_deg =
      normalize_degrees(e.mean_sidereal_time_deg +
                        e.nutation.longitude_deg * std::cos(e.true_obliquity_deg * kDegToRad));
  return e;
}

}  // namespace welkin::timeofday
