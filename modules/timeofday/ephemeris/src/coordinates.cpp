#include "welkin/timeofday/coordinates.h"

#include <cmath>

namespace welkin::timeofday {

double normalize_degrees(double degrees) {
  double r = std::fmod(degrees, 360.0);
  if (r < 0.0) r += 360.0;
  // fmod of a tiny negative number plus 360 rounds to exactly 360.
  return r >= 360.0 ? 0.0 : r;
}

double normalize_degrees_signed(double degrees) {
  const double r = normalize_degrees(degrees);
  return r > 180.0 ? r - 360.0 : r;
}

Equatorial ecliptic_to_equatorial(double longitude_deg, double latitude_deg, double obliquity_deg) {
  const double l = longitude_deg * kDegToRad;
  const double b = latitude_deg * kDegToRad;
  const double e = obliquity_deg * kDegToRad;
  // The tan(beta) of SPA eq. 38 is multiplied through by cos(beta) > 0, which keeps the quadrant
  // and avoids the pole singularity.
  const double y = std::sin(l) * std::cos(b) * std::cos(e) - std::sin(b) * std::sin(e);
  const double x = std::cos(l) * std::cos(b);
  const double z = std::sin(b) * std::cos(e) + std::cos(b) * std::sin(e) * std::sin(l);
  return {normalize_degrees(std::atan2(y, x) * kRadToDeg), std::asin(z) * kRadToDeg};
}

double angular_separation_deg(const Equatorial& a, const Equatorial& b) {
  const double ra1 = a.ra_deg * kDegToRad, dec1 = a.dec_deg * kDegToRad;
  const double ra2 = b.ra_deg * kDegToRad, dec2 = b.dec_deg * kDegToRad;
  const double u[3] = {std::cos(dec1) * std::cos(ra1), std::cos(dec1) * std::sin(ra1),
                       std::sin(dec1)};
  const double v[3] = {std::cos(dec2) * std::cos(ra2), std::cos(dec2) * std::sin(ra2),
                       std::sin(dec2)};
  const double cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0]};
  const double sin_angle =
      std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const double cos_angle = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  return std::atan2(sin_angle, cos_angle) * kRadToDeg;
}

std::array<double, 3> enu_direction(double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * kDegToRad;
  const double el = elevation_deg * kDegToRad;
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

}  // namespace welkin::timeofday
