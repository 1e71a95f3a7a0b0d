#include "reference/transmittance.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "reference/ray_geometry.h"

namespace welkin::atmosphere::reference {

QuadratureResult optical_depth(const AtmosphereModel& model, double r_km, double mu, double s0_km,
                               double s1_km, const QuadratureSettings& settings) {
  const double r = clamp_to_ground(model, r_km);
  const RayInterval interval = atmosphere_interval(model, r, mu);
  if (!interval.intersects) return {};
  const double a = std::max(s0_km, interval.start_km);
  const double b = std::min(s1_km, interval.end_km);
  if (!(b > a)) return {};
  const double bottom = model.bottom_radius_km;
  const std::vector<double> points = ray_breakpoints(model, r, mu, a, b);
  return integrate_gauss_kronrod(
      [&](double s) { return model.extinction(altitude_along_ray(bottom, r, mu, s)); }, points,
      settings);
}

QuadratureResult optical_depth_to_boundary(const AtmosphereModel& model, double r_km, double mu,
                                           const QuadratureSettings& settings) {
  const RayInterval interval = atmosphere_interval(model, r_km, mu);
  return optical_depth(model, r_km, mu, interval.start_km, interval.end_km, settings);
}

glm::dvec3 transmittance_to_boundary(const AtmosphereModel& model, double r_km, double mu,
                                     const QuadratureSettings& settings) {
  return glm::exp(-optical_depth_to_boundary(model, r_km, mu, settings).value);
}

glm::dvec3 transmittance_between(const AtmosphereModel& model, double r_km, double mu,
                                 double distance_km, const QuadratureSettings& settings) {
  return glm::exp(-optical_depth(model, r_km, mu, 0.0, distance_km, settings).value);
}

glm::dvec3 transmittance_to_sun(const AtmosphereModel& model, double r_km, double mu_s,
                                const QuadratureSettings& settings) {
  const double r = clamp_to_ground(model, r_km);
  if (ray_hits_sphere_below(model.bottom_radius_km, r, mu_s)) return glm::dvec3(0.0);
  return glm::exp(-optical_depth_to_boundary(model, r, mu_s, settings).value);
}

}  // namespace welkin::atmosphere::reference
