// Monte Carlo reference for clouds, all orders of scattering: radiance along a camera ray through a
// medium lit by a directional sun, a uniform sky and a uniform ground, and the reflected /
// transmitted flux of a slab.
//
// Free flight by delta tracking; at every scattering vertex the sun by next-event estimation with
// a ratio-tracking shadow ray; the next direction by exact phase sampling; escaping paths collect
// the sky or the ground; Russian roulette on the path weight after a few vertices. The direct sun
// is a delta and never seen by the camera ray itself.
//
// Determinism: paths are drawn in batches of batch_size, each batch with its own random stream
// (seed, batch index) and batch sums are added in batch order, so a result depends on (seed,
// samples, batch_size) only, never on the thread count or scheduling.
#pragma once

#include <cstdint>

#include "reference/estimate.h"
#include "reference/lighting.h"
#include "reference/medium.h"
#include "reference/phase.h"

namespace welkin::clouds::reference {

struct PathTraceSettings {
  std::uint64_t samples = 1u << 16;  // Paths.
  std::uint64_t seed = 1;            // Same seed, samples, batch_size: bitwise the same result.
  int max_orders = 1000;             // Scattering vertices per path; 1 = single scattering only.
  int roulette_start_order = 4;      // Vertices before Russian roulette on the path weight.
  int threads = 2;                   // Workers drawing batches.
  std::uint64_t batch_size = 256;    // Paths per random stream; part of the result's identity.
  // Tentative collisions (free flights and shadow rays) per path before it is cut and counted in
  // truncated_paths: bounds the work in optically huge, conservative media.
  std::uint64_t max_steps_per_path = 1'000'000;
};

// Radiance towards the camera, in the units of sun irradiance (per sr) and sky radiance.
struct CloudRadianceEstimate {
  Estimate scattered;      // Light scattered at least once towards the camera.
  Estimate transmittance;  // Along the camera ray (ratio tracking).
  Estimate background;     // transmittance * sky or ground radiance: what reaches the camera from behind.
  double radiance() const { return scattered.mean + background.mean; }
  std::uint64_t samples = 0;
  double mean_scattering_events = 0.0;  // Per path.
  std::uint64_t truncated_paths = 0;    // Cut by max_steps_per_path (a bias: they lose light).
  std::uint64_t majorant_violations = 0;
  double wall_ms = 0.0;
};

// Radiance along `view` (view.direction points away from the camera, which may be inside).
CloudRadianceEstimate path_trace(const Medium& medium, const PhaseFunction& phase, const Ray& view,
                                 const Lighting& lighting, const PathTraceSettings& settings = {});

// Fate of the sun's photons falling on a medium confined between two horizontal planes, as
// fractions of the incident flux. Their sum is 1 within the estimates' error (bar truncation).
struct SlabFluxEstimate {
  Estimate reflected;            // Left the medium upwards.
  Estimate transmitted_direct;   // Left downwards without scattering.
  Estimate transmitted_diffuse;  // Left downwards after scattering.
  Estimate absorbed;
  std::uint64_t samples = 0;
  std::uint64_t truncated_paths = 0;
  double wall_ms = 0.0;
};

// Photons enter at (0, 0, z_top) travelling along -sun_direction (which must point upwards) and are
// followed by the same delta tracking and phase sampling as path_trace until they leave; for a
// horizontally uniform medium the entry point is immaterial. Absorption is carried as weight.
SlabFluxEstimate slab_flux(const Medium& medium, const PhaseFunction& phase, double z_top,
                           const glm::dvec3& sun_direction, const PathTraceSettings& settings = {});

}  // namespace welkin::clouds::reference
