// Monte Carlo reference for all orders of scattering in the same atmosphere as the quadratures.
//
// Free flight: spectral tracking (Kutz et al. 2017) in RGB against the constant majorant
// max_extinction() (valid because densities are clamped to 1), with history-aware collision
// probabilities and absorption folded into the path weight, so one path serves all three
// channels without bias. At every scattering vertex (Rayleigh, Mie or a Lambertian ground
// bounce) the sun is added by next-event estimation with a shadow-ray transmittance computed by
// adaptive quadrature (transmittance.h), zero in the planet's shadow. Russian roulette after
// russian_roulette_start_order vertices. Sun illuminance 1, radiance in 1/sr.
//
// Determinism: samples are split into fixed chunks of chunk_size, each with its own RNG seeded
// from (seed, chunk index), and chunk sums are added in chunk order, so a result depends on
// (seed, samples, chunk_size) only: not on the thread count or scheduling.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>

#include "reference/atmosphere_model.h"
#include "reference/gauss_kronrod.h"

namespace welkin::atmosphere::reference {

struct PathTraceSettings {
  std::uint64_t samples = 1u << 16;  // Paths.
  std::uint64_t seed = 1;            // Same seed and samples: bitwise the same result.
  int max_order = 1000;              // Scattering vertices per path; 1 = single scattering only.
  int russian_roulette_start_order = 3;  // Vertices before roulette on max(weight) starts.
  int threads = 2;                       // std::thread workers pulling chunks.
  std::uint64_t chunk_size = 512;        // Paths per RNG stream; part of the result's identity.
  // When true, the ground seen directly by the camera reflects sun and sky too (full radiance,
  // for energy checks). Off by default to match single_scattering(), which excludes it.
  bool camera_sees_ground = false;
  // Shadow-ray optical depth tolerance: it only needs to be far below the Monte Carlo noise.
  QuadratureSettings shadow_ray{.relative_tolerance = 1e-7, .absolute_tolerance = 1e-12};
  // Tentative collisions per path before it is cut (counted in truncated_paths); a guard
  // against near-endless walks in conservative, optically huge atmospheres.
  std::uint64_t max_collisions_per_path = 10'000'000;
};

// Estimate of the radiance along the view ray for a sun of illuminance 1.
struct PathTraceResult {
  glm::dvec3 radiance{0.0};  // Mean, 1/sr.
  glm::dvec3 ci95{0.0};      // 95% confidence half-width of the mean, 1.96 standard errors.
  std::uint64_t samples = 0;
  double mean_vertices = 0.0;  // Scattering vertices per path (medium and ground).
  std::uint64_t truncated_paths = 0;
  double wall_ms = 0.0;
};

// camera_km is planet-centred (moved up to the ground if below it); view_dir and sun_dir are
// unit vectors, sun_dir pointing towards the sun.
PathTraceResult path_trace(const AtmosphereModel& model, const glm::dvec3& camera_km,
                           const glm::dvec3& view_dir, const glm::dvec3& sun_dir,
                           const PathTraceSettings& settings = {});

}  // namespace welkin::atmosphere::reference
