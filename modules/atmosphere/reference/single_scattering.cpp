#include "reference/single_scattering.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "reference/ray_geometry.h"
#include "reference/transmittance.h"

namespace welkin::atmosphere::reference {

namespace {

// Distances where camera + s view crosses the surface of the planet's shadow: the half cylinder
// behind the planet, along -sun, of the radius ray_hits_sphere_below() implies. Sunlight jumps
// to 0 there.
void add_shadow_crossings(std::vector<double>& points, double bottom_radius,
                          const glm::dvec3& camera, const glm::dvec3& view, const glm::dvec3& sun,
                          double s0, double s1) {
  const glm::dvec3 c_perp = camera - glm::dot(camera, sun) * sun;
  const glm::dvec3 v_perp = view - glm::dot(view, sun) * sun;
  const double a = glm::dot(v_perp, v_perp);
  if (a <= 0.0) return;  // Ray parallel to the sun: no crossing.
  const double b = glm::dot(c_perp, v_perp);
  const double c =
      glm::dot(c_perp, c_perp) - (1.0 - kTangentTolerance) * bottom_radius * bottom_radius;
  const double d = b * b - a * c;
  if (d < 0.0) return;
  for (double s : {(-b - std::sqrt(d)) / a, (-b + std::sqrt(d)) / a}) {
    if (s > s0 && s < s1 && glm::dot(camera + s * view, sun) < 0.0) points.push_back(s);
  }
}

}  // namespace

SingleScatteringResult single_scattering(const AtmosphereModel& model, const glm::dvec3& camera_km,
                                         const glm::dvec3& view_dir, const glm::dvec3& sun_dir,
                                         const SingleScatteringSettings& settings) {
  const double bottom = model.bottom_radius_km;
  glm::dvec3 camera = camera_km;
  const double camera_r = glm::length(camera);
  if (camera_r < bottom)
    camera = camera_r > 0.0 ? camera * (bottom / camera_r) : glm::dvec3(0, 0, bottom);
  const glm::dvec3 view = glm::normalize(view_dir);
  const glm::dvec3 sun = glm::normalize(sun_dir);
  const auto [r, mu] = radius_mu(camera, view);

  SingleScatteringResult result;
  const RayInterval interval = atmosphere_interval(model, r, mu);
  if (!interval.intersects) return result;
  const double s0 = interval.start_km;
  const double s1 = std::min(interval.end_km, settings.max_distance_km);
  if (!(s1 > s0)) return result;

  std::vector<double> points = ray_breakpoints(model, r, mu, s0, s1);
  add_shadow_crossings(points, bottom, camera, view, sun, s0, s1);
  // In optically thick media all the light comes from within a few mean free paths of the
  // entry point, a layer the first Kronrod nodes could step over entirely: split there.
  const double majorant = model.max_extinction();
  for (double depth = 1.0; majorant > 0.0 && s0 + depth / majorant < s1; depth *= 8.0) {
    points.push_back(s0 + depth / majorant);
  }
  std::sort(points.begin(), points.end());

  const double nu = glm::dot(view, sun);
  const double rayleigh_p = rayleigh_phase(nu);
  const double mie_p = model.mie_phase_value(nu);
  const auto integrand = [&](double s) -> glm::dvec3 {
    const LocalCoefficients k = model.coefficients(altitude_along_ray(bottom, r, mu, s));
    const glm::dvec3 scattering = k.rayleigh_scattering * rayleigh_p + k.mie_scattering * mie_p;
    if (scattering == glm::dvec3(0.0)) return glm::dvec3(0.0);
    const glm::dvec3 x = camera + s * view;
    const double rx = radius_along_ray(r, mu, s);
    const glm::dvec3 sunlight = transmittance_to_sun(
        model, rx, std::clamp(glm::dot(x, sun) / rx, -1.0, 1.0), settings.inner);
    if (sunlight == glm::dvec3(0.0)) return glm::dvec3(0.0);
    const glm::dvec3 view_t = glm::exp(-optical_depth(model, r, mu, s0, s, settings.inner).value);
    return view_t * sunlight * scattering;
  };
  const QuadratureResult q = integrate_gauss_kronrod(integrand, points, settings.outer);
  result.radiance = glm::max(q.value, glm::dvec3(0.0));
  result.error_estimate = q.error;
  result.evaluations = q.evaluations;
  result.converged = q.converged;
  result.transmittance = glm::exp(-optical_depth(model, r, mu, s0, s1, settings.inner).value);
  return result;
}

SingleScatteringResult single_scattering(const AtmosphereModel& model, double r_km, double mu,
                                         double mu_s, double nu,
                                         const SingleScatteringSettings& settings) {
  mu = std::clamp(mu, -1.0, 1.0);
  mu_s = std::clamp(mu_s, -1.0, 1.0);
  const double sin_view = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
  const double sin_sun = std::sqrt(std::max(0.0, (1.0 - mu_s) * (1.0 + mu_s)));
  // Sun in the frame where the view lies in the x-z plane; x component from nu.
  double sun_x = sin_sun;
  if (sin_view > 0.0) sun_x = std::clamp((nu - mu * mu_s) / sin_view, -sin_sun, sin_sun);
  const double sun_y = std::sqrt(std::max(0.0, sin_sun * sin_sun - sun_x * sun_x));
  return single_scattering(model, glm::dvec3(0.0, 0.0, r_km), glm::dvec3(sin_view, 0.0, mu),
                           glm::dvec3(sun_x, sun_y, mu_s), settings);
}

}  // namespace welkin::atmosphere::reference
