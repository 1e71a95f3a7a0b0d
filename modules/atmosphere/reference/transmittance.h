// Optical depth and transmittance by adaptive Gauss-Kronrod quadrature along a ray given by the
// radius r of its origin and the cosine mu of its zenith angle (see ray_geometry.h).
//
// Tolerance: by default the optical depth tau of each channel is converged to a relative error
// of 1e-9 (absolute floor 1e-13), measured by the conservative |K15 - G7| estimate, so the
// transmittance exp(-tau) is accurate to a relative 1e-9 * tau: better than 1e-6 for tau < 1000.
// Pieces are split at the profiles' kink altitudes and at the ray's lowest point first.
#pragma once

#include <glm/vec3.hpp>

#include "reference/atmosphere_model.h"
#include "reference/gauss_kronrod.h"

namespace welkin::atmosphere::reference {

inline constexpr QuadratureSettings kOpticalDepthTolerance{.relative_tolerance = 1e-9,
                                                           .absolute_tolerance = 1e-13};

// Optical depth over distances [s0, s1] along the ray, clipped to its visible atmospheric
// interval (so nothing beyond the ground hit counts). An origin under the ground is clamped up.
QuadratureResult optical_depth(const AtmosphereModel& model, double r_km, double mu, double s0_km,
                               double s1_km,
                               const QuadratureSettings& settings = kOpticalDepthTolerance);

// Optical depth from the origin to the end of the ray: the ground if it hits it, else the top.
// Zero when a ray from space misses the atmosphere.
QuadratureResult optical_depth_to_boundary(
    const AtmosphereModel& model, double r_km, double mu,
    const QuadratureSettings& settings = kOpticalDepthTolerance);

// exp(-optical depth) from the origin to the ray's end (ground or top); 1 if it misses.
glm::dvec3 transmittance_to_boundary(const AtmosphereModel& model, double r_km, double mu,
                                     const QuadratureSettings& settings = kOpticalDepthTolerance);

// Transmittance between the origin and the point at distance_km along the ray, the distance
// clamped to the ray's end. Non-increasing in distance_km.
glm::dvec3 transmittance_between(const AtmosphereModel& model, double r_km, double mu,
                                 double distance_km,
                                 const QuadratureSettings& settings = kOpticalDepthTolerance);

// Transmittance of sunlight reaching radius r from a sun at zenith cosine mu_s: 0 when the
// planet blocks the (point) sun, else transmittance to the top.
glm::dvec3 transmittance_to_sun(const AtmosphereModel& model, double r_km, double mu_s,
                                const QuadratureSettings& settings = kOpticalDepthTolerance);

}  // namespace welkin::atmosphere::reference
