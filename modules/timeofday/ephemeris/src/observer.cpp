#include "welkin/timeofday/observer.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace welkin::timeofday {
namespace {

// Polar over equatorial radius and equatorial radius in metres, as SPA (eqs. 34-36) uses them.
constexpr double kEarthPolarRatio = 0.99664719;
constexpr double kEarthEquatorialRadiusM = 6378140.0;

std::string number(double v) {
  if (std::isnan(v)) return "NaN";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

}  // namespace

std::optional<std::string> validate(const Observer& o) {
  if (!std::isfinite(o.latitude_deg) || o.latitude_deg < -90.0 || o.latitude_deg > 90.0) {
    return "observer latitude " + number(o.latitude_deg) + " deg is outside [-90, 90]";
  }
  if (!std::isfinite(o.longitude_deg) || o.longitude_deg < -180.0 || o.longitude_deg > 180.0) {
    return "observer longitude " + number(o.longitude_deg) + " deg is outside [-180, 180]";
  }
  if (!std::isfinite(o.elevation_m) || o.elevation_m < kMinElevationM ||
      o.elevation_m > kMaxElevationM) {
    return "observer elevation " + number(o.elevation_m) + " m is outside [" +
           number(kMinElevationM) + ", " + number(kMaxElevationM) + "]";
  }
  if (!std::isfinite(o.pressure_mbar) || o.pressure_mbar < 0.0 ||
      o.pressure_mbar > kMaxPressureMbar) {
    return "observer pressure " + number(o.pressure_mbar) + " mbar is outside [0, " +
           number(kMaxPressureMbar) + "]";
  }
  if (!std::isfinite(o.temperature_c) || o.temperature_c < kMinTemperatureC ||
      o.temperature_c > kMaxTemperatureC) {
    return "observer temperature " + number(o.temperature_c) + " C is outside [" +
           number(kMinTemperatureC) + ", " + number(kMaxTemperatureC) + "]";
  }
  return std::nullopt;
}

double refraction_correction_deg(double true_elevation_deg, double pressure_mbar,
                                 double temperature_c, const RefractionSettings& settings) {
  if (!settings.enabled) return 0.0;
  // Below this the body is invisible anyway and the formula's pole at e0 = -5.11 lies near.
  if (true_elevation_deg < -(settings.body_radius_deg + settings.horizon_refraction_deg)) {
    return 0.0;
  }
  const double e0 = true_elevation_deg;
  return (pressure_mbar / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02 /
         (60.0 * std::tan((e0 + 10.3 / (e0 + 5.11)) * kDegToRad));
}

TopocentricPosition observe(const Equatorial& geocentric, double sin_parallax,
                            const EarthOrientation& earth, const Observer& observer,
                            const RefractionSettings& refraction) {
  TopocentricPosition p;
  const double lat = observer.latitude_deg * kDegToRad;
  // SPA eq. 32: hour angle measured westward from the meridian.
  p.hour_angle_deg = normalize_degrees(earth.apparent_sidereal_time_deg + observer.longitude_deg -
                                       geocentric.ra_deg);

  // The observer's geocentric position in Earth radii: rho cos(phi') and rho sin(phi').
  const double u = std::atan2(kEarthPolarRatio * std::sin(lat), std::cos(lat));
  const double h = observer.elevation_m / kEarthEquatorialRadiusM;
  const double x = std::cos(u) + h * std::cos(lat);
  const double y = kEarthPolarRatio * std::sin(u) + h * std::sin(lat);

  // Meeus ch. 40 in its rigorous vector form: the body's direction seen from the observer, in
  // units of its geocentric distance. It equals SPA eqs. 37-39 and also gives the distance.
  const double hour = p.hour_angle_deg * kDegToRad;
  const double dec = geocentric.dec_deg * kDegToRad;
  const double a = std::cos(dec) * std::sin(hour);
  const double b = std::cos(dec) * std::cos(hour) - x * sin_parallax;
  const double c = std::sin(dec) - y * sin_parallax;
  const double horizontal = std::hypot(a, b);
  p.distance_ratio = std::hypot(horizontal, c);
  const double topo_hour = std::atan2(a, b);
  const double topo_dec = std::atan2(c, horizontal);
  p.topocentric_hour_angle_deg = normalize_degrees(topo_hour * kRadToDeg);
  p.ra_parallax_deg = normalize_degrees_signed(p.hour_angle_deg - p.topocentric_hour_angle_deg);
  p.equatorial = {normalize_degrees(geocentric.ra_deg + p.ra_parallax_deg), topo_dec * kRadToDeg};

  // SPA eqs. 41-47: horizontal coordinates. The tan(delta') of eq. 45 is multiplied through by
  // cos(delta') > 0 so a body near a celestial pole stays finite.
  const double sin_e0 =
      std::sin(lat) * std::sin(topo_dec) + std::cos(lat) * std::cos(topo_dec) * std::cos(topo_hour);
  p.true_elevation_deg = std::asin(std::fmax(-1.0, std::fmin(1.0, sin_e0))) * kRadToDeg;
  p.refraction_deg = refraction_correction_deg(p.true_elevation_deg, observer.pressure_mbar,
                                               observer.temperature_c, refraction);
  p.elevation_deg = p.true_elevation_deg + p.refraction_deg;
  p.zenith_deg = 90.0 - p.elevation_deg;
  const double gamma = std::atan2(std::sin(topo_hour) * std::cos(topo_dec),
                                  std::cos(topo_hour) * std::sin(lat) * std::cos(topo_dec) -
                                      std::sin(topo_dec) * std::cos(lat));
  p.azimuth_deg = normalize_degrees(gamma * kRadToDeg + 180.0);
  return p;
}

}  // namespace welkin::timeofday
