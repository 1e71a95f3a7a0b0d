#include "welkin/timeofday/moon.h"

#include <cmath>
#include <stdexcept>

namespace welkin::timeofday {
namespace {

// Meeus Table 47.A: multiples of (D, M, M', F); Sigma-l coefficient in 1e-6 degree (sine) and
// Sigma-r coefficient in metres (cosine).
struct LongitudeDistanceTerm {
  signed char m[4];
  double l;
  double r;
};

// Meeus Table 47.B: multiples of (D, M, M', F); Sigma-b coefficient in 1e-6 degree (sine).
struct LatitudeTerm {
  signed char m[4];
  double b;
};

constexpr LongitudeDistanceTerm kLongitudeDistanceTerms[60] = {
    {{0, 0, 1, 0}, 6288774.0, -20905355.0},
    {{2, 0, -1, 0}, 1274027.0, -3699111.0},
    {{2, 0, 0, 0}, 658314.0, -2955968.0},
    {{0, 0, 2, 0}, 213618.0, -569925.0},
    {{0, 1, 0, 0}, -185116.0, 48888.0},
    {{0, 0, 0, 2}, -114332.0, -3149.0},
    {{2, 0, -2, 0}, 58793.0, 246158.0},
    {{2, -1, -1, 0}, 57066.0, -152138.0},
    {{2, 0, 1, 0}, 53322.0, -170733.0},
    {{2, -1, 0, 0}, 45758.0, -204586.0},
    {{0, 1, -1, 0}, -40923.0, -129620.0},
    {{1, 0, 0, 0}, -34720.0, 108743.0},
    {{0, 1, 1, 0}, -30383.0, 104755.0},
    {{2, 0, 0, -2}, 15327.0, 10321.0},
    {{0, 0, 1, 2}, -12528.0, 0.0},
    {{0, 0, 1, -2}, 10980.0, 79661.0},
    {{4, 0, -1, 0}, 10675.0, -34782.0},
    {{0, 0, 3, 0}, 10034.0, -23210.0},
    {{4, 0, -2, 0}, 8548.0, -21636.0},
    {{2, 1, -1, 0}, -7888.0, 24208.0},
    {{2, 1, 0, 0}, -6766.0, 30824.0},
    {{1, 0, -1, 0}, -5163.0, -8379.0},
    {{1, 1, 0, 0}, 4987.0, -16675.0},
    {{2, -1, 1, 0}, 4036.0, -12831.0},
    {{2, 0, 2, 0}, 3994.0, -10445.0},
    {{4, 0, 0, 0}, 3861.0, -11650.0},
    {{2, 0, -3, 0}, 3665.0, 14403.0},
    {{0, 1, -2, 0}, -2689.0, -7003.0},
    {{2, 0, -1, 2}, -2602.0, 0.0},
    {{2, -1, -2, 0}, 2390.0, 10056.0},
    {{1, 0, 1, 0}, -2348.0, 6322.0},
    {{2, -2, 0, 0}, 2236.0, -9884.0},
    {{0, 1, 2, 0}, -2120.0, 5751.0},
    {{0, 2, 0, 0}, -2069.0, 0.0},
    {{2, -2, -1, 0}, 2048.0, -4950.0},
    {{2, 0, 1, -2}, -1773.0, 4130.0},
    {{2, 0, 0, 2}, -1595.0, 0.0},
    {{4, -1, -1, 0}, 1215.0, -3958.0},
    {{0, 0, 2, 2}, -1110.0, 0.0},
    {{3, 0, -1, 0}, -892.0, 3258.0},
    {{2, 1, 1, 0}, -810.0, 2616.0},
    {{4, -1, -2, 0}, 759.0, -1897.0},
    {{0, 2, -1, 0}, -713.0, -2117.0},
    {{2, 2, -1, 0}, -700.0, 2354.0},
    {{2, 1, -2, 0}, 691.0, 0.0},
    {{2, -1, 0, -2}, 596.0, 0.0},
    {{4, 0, 1, 0}, 549.0, -1423.0},
    {{0, 0, 4, 0}, 537.0, -1117.0},
    {{4, -1, 0, 0}, 520.0, -1571.0},
    {{1, 0, -2, 0}, -487.0, -1739.0},
    {{2, 1, 0, -2}, -399.0, 0.0},
    {{0, 0, 2, -2}, -381.0, -4421.0},
    {{1, 1, 1, 0}, 351.0, 0.0},
    {{3, 0, -2, 0}, -340.0, 0.0},
    {{4, 0, -3, 0}, 330.0, 0.0},
    {{2, -1, 2, 0}, 327.0, 0.0},
    {{0, 2, 1, 0}, -323.0, 1165.0},
    {{1, 1, -1, 0}, 299.0, 0.0},
    {{2, 0, 3, 0}, 294.0, 0.0},
    {{2, 0, -1, -2}, 0.0, 8752.0},
};

constexpr LatitudeTerm kLatitudeTerms[60] = {
    {{0, 0, 0, 1}, 5128122.0}, {{0, 0, 1, 1}, 280602.0},  {{0, 0, 1, -1}, 277693.0},
    {{2, 0, 0, -1}, 173237.0}, {{2, 0, -1, 1}, 55413.0},  {{2, 0, -1, -1}, 46271.0},
    {{2, 0, 0, 1}, 32573.0},   {{0, 0, 2, 1}, 17198.0},   {{2, 0, 1, -1}, 9266.0},
    {{0, 0, 2, -1}, 8822.0},   {{2, -1, 0, -1}, 8216.0},  {{2, 0, -2, -1}, 4324.0},
    {{2, 0, 1, 1}, 4200.0},    {{2, 1, 0, -1}, -3359.0},  {{2, -1, -1, 1}, 2463.0},
    {{2, -1, 0, 1}, 2211.0},   {{2, -1, -1, -1}, 2065.0}, {{0, 1, -1, -1}, -1870.0},
    {{4, 0, -1, -1}, 1828.0},  {{0, 1, 0, 1}, -1794.0},   {{0, 0, 0, 3}, -1749.0},
    {{0, 1, -1, 1}, -1565.0},  {{1, 0, 0, 1}, -1491.0},   {{0, 1, 1, 1}, -1475.0},
    {{0, 1, 1, -1}, -1410.0},  {{0, 1, 0, -1}, -1344.0},  {{1, 0, 0, -1}, -1335.0},
    {{0, 0, 3, 1}, 1107.0},    {{4, 0, 0, -1}, 1021.0},   {{4, 0, -1, 1}, 833.0},
    {{0, 0, 1, -3}, 777.0},    {{4, 0, -2, 1}, 671.0},    {{2, 0, 0, -3}, 607.0},
    {{2, 0, 2, -1}, 596.0},    {{2, -1, 1, -1}, 491.0},   {{2, 0, -2, 1}, -451.0},
    {{0, 0, 3, -1}, 439.0},    {{2, 0, 2, 1}, 422.0},     {{2, 0, -3, -1}, 421.0},
    {{2, 1, -1, 1}, -366.0},   {{2, 1, 0, 1}, -351.0},    {{4, 0, 0, 1}, 331.0},
    {{2, -1, 1, 1}, 315.0},    {{2, -2, 0, -1}, 302.0},   {{0, 0, 1, 3}, -283.0},
    {{2, 1, 1, -1}, -229.0},   {{1, 1, 0, -1}, 223.0},    {{1, 1, 0, 1}, 223.0},
    {{0, 1, -2, -1}, -220.0},  {{2, 1, -1, -1}, -220.0},  {{1, 0, 1, 1}, -185.0},
    {{2, -1, -2, -1}, 181.0},  {{0, 1, 2, 1}, -177.0},    {{4, 0, -2, -1}, 176.0},
    {{4, -1, -1, -1}, 166.0},  {{1, 0, 1, -1}, -164.0},   {{4, 0, 1, -1}, 132.0},
    {{1, 0, -1, -1}, -119.0},  {{4, -1, 0, -1}, 115.0},   {{2, -2, 0, 1}, 107.0},
};

// Terms that involve the sun's mean anomaly M shrink with Earth's decreasing orbital eccentricity:
// multiply by E for |M| = 1 and by E^2 for |M| = 2 (Meeus eq. 47.6).
double eccentricity_factor(int sun_anomaly_multiple, double e) {
  const int n = sun_anomaly_multiple < 0 ? -sun_anomaly_multiple : sun_anomaly_multiple;
  return n == 0 ? 1.0 : (n == 1 ? e : e * e);
}

}  // namespace

MoonGeocentric moon_geocentric(const EarthOrientation& earth) {
  const double t = earth.jce;
  // Meeus eqs. 47.1-47.5: the fundamental arguments, degrees.
  const double lp = normalize_degrees(
      218.3164477 +
      t * (481267.88123421 + t * (-0.0015786 + t * (1.0 / 538841.0 - t / 65194000.0))));
  const double d = normalize_degrees(
      297.8501921 +
      t * (445267.1114034 + t * (-0.0018819 + t * (1.0 / 545868.0 - t / 113065000.0))));
  const double m =
      normalize_degrees(357.5291092 + t * (35999.0502909 + t * (-0.0001536 + t / 24490000.0)));
  const double mp = normalize_degrees(
      134.9633964 + t * (477198.8675055 + t * (0.0087414 + t * (1.0 / 69699.0 - t / 14712000.0))));
  const double f = normalize_degrees(
      93.2720950 +
      t * (483202.0175233 + t * (-0.0036539 + t * (-1.0 / 3526000.0 + t / 863310000.0))));
  // Additive arguments: Venus (A1), Jupiter (A2) and the flattening of the Earth (A3).
  const double a1 = normalize_degrees(119.75 + 131.849 * t) * kDegToRad;
  const double a2 = normalize_degrees(53.09 + 479264.290 * t) * kDegToRad;
  const double a3 = normalize_degrees(313.45 + 481266.484 * t) * kDegToRad;
  const double e = 1.0 - t * (0.002516 + 0.0000074 * t);

  const double args[4] = {d * kDegToRad, m * kDegToRad, mp * kDegToRad, f * kDegToRad};
  double sum_l = 0.0;
  double sum_r = 0.0;
  for (const LongitudeDistanceTerm& term : kLongitudeDistanceTerms) {
    double angle = 0.0;
    for (int k = 0; k < 4; ++k) angle += term.m[k] * args[k];
    const double scale = eccentricity_factor(term.m[1], e);
    sum_l += term.l * scale * std::sin(angle);
    sum_r += term.r * scale * std::cos(angle);
  }
  double sum_b = 0.0;
  for (const LatitudeTerm& term : kLatitudeTerms) {
    double angle = 0.0;
    for (int k = 0; k < 4; ++k) angle += term.m[k] * args[k];
    sum_b += term.b * eccentricity_factor(term.m[1], e) * std::sin(angle);
  }
  const double lp_rad = lp * kDegToRad;
  const double f_rad = args[3];
  const double mp_rad = args[2];
  sum_l += 3958.0 * std::sin(a1) + 1962.0 * std::sin(lp_rad - f_rad) + 318.0 * std::sin(a2);
  sum_b += -2235.0 * std::sin(lp_rad) + 382.0 * std::sin(a3) + 175.0 * std::sin(a1 - f_rad) +
           175.0 * std::sin(a1 + f_rad) + 127.0 * std::sin(lp_rad - mp_rad) -
           115.0 * std::sin(lp_rad + mp_rad);

  MoonGeocentric moon;
  moon.mean_longitude_deg = lp;
  moon.longitude_deg = normalize_degrees(lp + sum_l / 1.0e6);
  moon.latitude_deg = sum_b / 1.0e6;
  moon.distance_km = 385000.56 + sum_r / 1000.0;
  moon.horizontal_parallax_deg = std::asin(kEarthEquatorialRadiusKm / moon.distance_km) * kRadToDeg;
  // Nutation in longitude makes the position apparent; the moon's aberration (~0.7") is left
  // out, as Meeus does.
  moon.apparent_longitude_deg =
      normalize_degrees(moon.longitude_deg + earth.nutation.longitude_deg);
  moon.equatorial = ecliptic_to_equatorial(moon.apparent_longitude_deg, moon.latitude_deg,
                                           earth.true_obliquity_deg);
  return moon;
}

LunarPhase lunar_phase(const MoonGeocentric& moon, const SunGeocentric& sun) {
  LunarPhase phase;
  phase.elongation_deg = angular_separation_deg(sun.equatorial, moon.equatorial);
  const double psi = phase.elongation_deg * kDegToRad;
  const double r = sun.distance_au * kAstronomicalUnitKm;
  // Meeus eq. 48.3 in atan2 form, so the quadrant is right at any elongation.
  const double i = std::atan2(r * std::sin(psi), moon.distance_km - r * std::cos(psi));
  phase.phase_angle_deg = i * kRadToDeg;
  phase.illuminated_fraction = (1.0 + std::cos(i)) / 2.0;
  return phase;
}

double angular_radius_deg(double radius_km, double distance_km) {
  if (!(radius_km >= 0.0) || !(distance_km > radius_km) || !std::isfinite(distance_km)) {
    throw std::invalid_argument("angular_radius_deg: need 0 <= radius < distance, both finite");
  }
  return std::asin(radius_km / distance_km) * kRadToDeg;
}

}  // namespace welkin::timeofday
