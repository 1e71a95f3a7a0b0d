// Single-scattered radiance along a view ray, by nested adaptive quadrature:
//   L = integral over the visible ray of T(camera -> x) sigma_s(x) p(theta) T_sun(x) ds
// for a directional (point) sun of illuminance 1 perpendicular to its direction, so L is in 1/sr.
// sigma_s p = Rayleigh + Mie; extinction includes absorption. T_sun = 0 in the planet's shadow.
// The directly seen ground adds nothing: this is light scattered by the air into the ray.
//
// Tolerance: the outer integral is converged to a relative 1e-7 per channel (|K15 - G7|
// estimate) and every inner optical depth to a relative 1e-10, so the result is accurate to
// about 1e-6 relative or better. The outer pieces are split at the profiles' kink altitudes,
// the ray's lowest point, where the ray enters or leaves the planet's shadow cylinder, and at
// 1, 8, 64... majorant mean free paths from the entry point (thick media).
#pragma once

#include <glm/vec3.hpp>
#include <limits>

#include "reference/atmosphere_model.h"
#include "reference/gauss_kronrod.h"

namespace welkin::atmosphere::reference {

// Outer (along the view ray) and inner (optical depths) quadrature tolerances.
struct SingleScatteringSettings {
  QuadratureSettings outer{.relative_tolerance = 1e-7, .absolute_tolerance = 1e-16};
  QuadratureSettings inner{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-14};
  // Integrate only the first max_distance_km of the visible ray (aerial perspective up to a
  // surface point); infinity for the whole ray.
  double max_distance_km = std::numeric_limits<double>::infinity();
};

// Radiance and the diagnostics a comparison table needs.
struct SingleScatteringResult {
  glm::dvec3 radiance{0.0};        // 1/sr, for sun illuminance 1.
  glm::dvec3 error_estimate{0.0};  // Outer quadrature's absolute error estimate.
  glm::dvec3 transmittance{1.0};   // Of the integrated segment, camera to its far end.
  int evaluations = 0;             // Outer integrand calls (each runs two inner quadratures).
  bool converged = true;
};

// camera_km is planet-centred (moved up to the ground if below it); view_dir and sun_dir are
// unit vectors, sun_dir pointing towards the sun.
SingleScatteringResult single_scattering(const AtmosphereModel& model, const glm::dvec3& camera_km,
                                         const glm::dvec3& view_dir, const glm::dvec3& sun_dir,
                                         const SingleScatteringSettings& settings = {});

// Bruneton's parametrisation: camera radius r, view zenith cosine mu, sun zenith cosine mu_s and
// nu = dot(view, sun). Inconsistent (mu, mu_s, nu) triples are clamped to the nearest valid one.
SingleScatteringResult single_scattering(const AtmosphereModel& model, double r_km, double mu,
                                         double mu_s, double nu,
                                         const SingleScatteringSettings& settings = {});

}  // namespace welkin::atmosphere::reference
