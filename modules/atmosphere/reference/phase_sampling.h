// Direction sampling for the path tracer, kept public so that each sampler can be checked against
// the phase function it claims to sample. Each takes two uniform numbers in [0, 1).
#pragma once

#include <glm/vec3.hpp>

#include "reference/atmosphere_model.h"

namespace welkin::atmosphere::reference {

// A sampled direction and its weight phase / pdf (1 when the phase function is sampled exactly).
struct PhaseSample {
  glm::dvec3 direction{0.0};
  double weight = 1.0;
};

// Unit vector at cos_theta from axis, at azimuth phi about it (in a basis built from axis alone).
glm::dvec3 direction_about(const glm::dvec3& axis, double cos_theta, double phi);

// Rayleigh, by exact inversion of its CDF (Cardano on mu^3 + 3 mu = 8 xi - 4).
PhaseSample sample_rayleigh(const glm::dvec3& forward, double xi_cos, double xi_phi);

// The model's Mie phase function: Henyey-Greenstein exactly; Cornette-Shanks through
// Henyey-Greenstein with the same g and weight CS / HG = 3 (1 + mu^2) / (2 (2 + g^2)) <= 1.5.
PhaseSample sample_mie(const AtmosphereModel& model, const glm::dvec3& forward, double xi_cos,
                       double xi_phi);

// Cosine-weighted direction about a surface normal: with it a Lambertian bounce's weight is the
// albedo (BRDF albedo / pi times cos over pdf cos / pi).
glm::dvec3 sample_cosine_hemisphere(const glm::dvec3& normal, double xi_cos, double xi_phi);

}  // namespace welkin::atmosphere::reference
