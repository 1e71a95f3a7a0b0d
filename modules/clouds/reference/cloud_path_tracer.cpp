#include "reference/cloud_path_tracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <thread>
#include <vector>

#include "reference/random_stream.h"
#include "reference/tracking.h"

namespace welkin::clouds::reference {

namespace {

// Runs settings.samples paths in batches over settings.threads workers; `trace_path(rng, sums)`
// adds one path to its batch's sums. Batches are merged in batch order: thread-count independent.
template <typename Sums, typename TracePath>
Sums run_batches(const PathTraceSettings& settings, const TracePath& trace_path) {
  const std::uint64_t batch_size = std::max<std::uint64_t>(settings.batch_size, 1);
  const std::uint64_t batches = (settings.samples + batch_size - 1) / batch_size;
  std::vector<Sums> per_batch(batches);
  std::atomic<std::uint64_t> next_batch{0};
  const auto worker = [&] {
    for (std::uint64_t b = next_batch++; b < batches; b = next_batch++) {
      RandomStream rng(settings.seed, b);
      const std::uint64_t end = std::min(settings.samples, (b + 1) * batch_size);
      for (std::uint64_t i = b * batch_size; i < end; ++i) trace_path(rng, per_batch[b]);
    }
  };
  const std::uint64_t threads = std::clamp<std::uint64_t>(
      static_cast<std::uint64_t>(std::max(settings.threads, 1)), 1, std::max<std::uint64_t>(batches, 1));
  std::vector<std::thread> pool;
  for (std::uint64_t i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  Sums total;
  for (const Sums& sums : per_batch) total.merge(sums);
  return total;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct RadianceSums {
  SampleSums scattered, transmittance;
  std::uint64_t events = 0, truncated = 0, violations = 0;
  void merge(const RadianceSums& o) {
    scattered.merge(o.scattered);
    transmittance.merge(o.transmittance);
    events += o.events;
    truncated += o.truncated;
    violations += o.violations;
  }
};

// One path's estimate of the light scattered at least once towards the camera.
class RadiancePath {
 public:
  RadiancePath(const Medium& medium, const PhaseFunction& phase, const Ray& view, const Lighting& lighting,
               const PathTraceSettings& settings)
      : medium_(medium), phase_(phase), view_(view), lighting_(lighting), settings_(settings) {}

  void operator()(RandomStream& rng, RadianceSums& sums) const {
    TrackingBudget budget{.remaining_steps = settings_.max_steps_per_path};
    sums.scattered.add(scattered(rng, budget, sums.events));
    if (budget.exhausted()) ++sums.truncated;
    // The camera ray's transmittance from the same stream, with a budget of its own.
    TrackingBudget camera_budget{.remaining_steps = settings_.max_steps_per_path};
    sums.transmittance.add(ratio_tracking_transmittance(medium_, view_, kInfinity, rng, camera_budget));
    sums.violations += budget.majorant_violations + camera_budget.majorant_violations;
  }

 private:
  double scattered(RandomStream& rng, TrackingBudget& budget, std::uint64_t& events) const {
    const glm::dvec3& sun = lighting_.sun_direction;
    Ray ray = view_;
    double weight = 1.0, radiance = 0.0;
    for (int order = 0;;) {
      const double t = sample_free_flight(medium_, ray, rng, budget);
      if (budget.exhausted()) return radiance;
      if (!std::isfinite(t)) {
        // Escaped: the sky or the ground, unless this is the camera ray itself (its background is
        // separate).
        if (order > 0) radiance += weight * lighting_.environment(ray.origin, ray.direction);
        return radiance;
      }
      const glm::dvec3 x = ray.at(t);
      weight *= medium_.single_scattering_albedo;
      ++order;
      ++events;
      if (lighting_.sun_irradiance > 0.0) {
        const double to_sun = ratio_tracking_transmittance(medium_, {x, sun}, kInfinity, rng, budget);
        radiance +=
            weight * lighting_.sun_irradiance * phase_.evaluate(glm::dot(ray.direction, sun)) * to_sun;
      }
      const glm::dvec3 next = phase_.sample_direction(ray.direction, rng);
      if (order >= settings_.max_orders) {
        // The last order still sees the sky or ground that reaches this vertex unscattered.
        if (const double outside = lighting_.environment(x, next); outside > 0.0)
          radiance +=
              weight * outside * ratio_tracking_transmittance(medium_, {x, next}, kInfinity, rng, budget);
        return radiance;
      }
      ray = {x, next};
      if (order >= settings_.roulette_start_order) {
        const double survive = std::min(1.0, weight);
        if (!(rng.uniform() < survive)) return radiance;
        weight /= survive;
      }
    }
  }

  const Medium& medium_;
  const PhaseFunction& phase_;
  Ray view_;
  Lighting lighting_;
  const PathTraceSettings& settings_;
};

struct FluxSums {
  SampleSums reflected, direct, diffuse, absorbed;
  std::uint64_t truncated = 0;
  void merge(const FluxSums& o) {
    reflected.merge(o.reflected);
    direct.merge(o.direct);
    diffuse.merge(o.diffuse);
    absorbed.merge(o.absorbed);
    truncated += o.truncated;
  }
};

}  // namespace

CloudRadianceEstimate path_trace(const Medium& medium, const PhaseFunction& phase, const Ray& view,
                                 const Lighting& lighting, const PathTraceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  Ray unit_view{view.origin, glm::normalize(view.direction)};
  Lighting unit_lighting = lighting;
  unit_lighting.sun_direction = glm::normalize(lighting.sun_direction);
  const RadiancePath path(medium, phase, unit_view, unit_lighting, settings);
  const RadianceSums sums = run_batches<RadianceSums>(settings, path);

  CloudRadianceEstimate result;
  result.samples = settings.samples;
  result.scattered = sums.scattered.estimate();
  result.transmittance = sums.transmittance.estimate();
  const double behind = lighting.environment(unit_view.origin, unit_view.direction);
  result.background = {result.transmittance.mean * behind, result.transmittance.ci95 * behind};
  if (settings.samples > 0) {
    result.mean_scattering_events = static_cast<double>(sums.events) / static_cast<double>(settings.samples);
  }
  result.truncated_paths = sums.truncated;
  result.majorant_violations = sums.violations;
  result.wall_ms = elapsed_ms(start);
  return result;
}

SlabFluxEstimate slab_flux(const Medium& medium, const PhaseFunction& phase, double z_top,
                           const glm::dvec3& sun_direction, const PathTraceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const glm::dvec3 incident = -glm::normalize(sun_direction);
  const auto trace_photon = [&](RandomStream& rng, FluxSums& sums) {
    TrackingBudget budget{.remaining_steps = settings.max_steps_per_path};
    Ray ray{{0.0, 0.0, z_top}, incident};
    double weight = 1.0, reflected = 0.0, direct = 0.0, diffuse = 0.0, absorbed = 0.0;
    for (int order = 0;;) {
      const double t = sample_free_flight(medium, ray, rng, budget);
      if (budget.exhausted()) {
        ++sums.truncated;
        break;
      }
      if (!std::isfinite(t)) {
        (ray.direction.z > 0.0 ? reflected : order == 0 ? direct : diffuse) = weight;
        break;
      }
      absorbed += weight * (1.0 - medium.single_scattering_albedo);
      weight *= medium.single_scattering_albedo;
      if (++order >= settings.max_orders) {
        ++sums.truncated;
        break;
      }
      ray = {ray.at(t), phase.sample_direction(ray.direction, rng)};
      if (order >= settings.roulette_start_order) {
        const double survive = std::min(1.0, weight);
        if (!(rng.uniform() < survive)) break;  // In expectation the weight is kept: unbiased.
        weight /= survive;
      }
    }
    sums.reflected.add(reflected);
    sums.direct.add(direct);
    sums.diffuse.add(diffuse);
    sums.absorbed.add(absorbed);
  };
  const FluxSums sums = run_batches<FluxSums>(settings, trace_photon);

  SlabFluxEstimate result;
  result.samples = settings.samples;
  result.reflected = sums.reflected.estimate();
  result.transmitted_direct = sums.direct.estimate();
  result.transmitted_diffuse = sums.diffuse.estimate();
  result.absorbed = sums.absorbed.estimate();
  result.truncated_paths = sums.truncated;
  result.wall_ms = elapsed_ms(start);
  return result;
}

}  // namespace welkin::clouds::reference
