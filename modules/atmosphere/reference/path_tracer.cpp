#include "reference/path_tracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <thread>
#include <vector>

#include "reference/phase_sampling.h"
#include "reference/ray_geometry.h"
#include "reference/transmittance.h"

namespace welkin::atmosphere::reference {

namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// xoshiro256** (Blackman and Vigna), seeded through splitmix64 as its authors recommend.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) {
    std::uint64_t mix = seed;
    std::uint64_t key = splitmix64(mix) ^ (stream * 0xD1B54A32D192ED03ull + 0x632BE59BD9B4E019ull);
    for (auto& word : s_) word = splitmix64(key);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  std::uint64_t s_[4];
};

double mean(const glm::dvec3& v) {
  return (v.x + v.y + v.z) / 3.0;
}

struct ChunkSums {
  glm::dvec3 sum{0.0};
  glm::dvec3 sum_sq{0.0};
  std::uint64_t vertices = 0;
  std::uint64_t truncated = 0;
};

class Tracer {
 public:
  Tracer(const AtmosphereModel& model, const glm::dvec3& camera, const glm::dvec3& view,
         const glm::dvec3& sun, const PathTraceSettings& settings)
      : model_(model),
        camera_(camera),
        view_(view),
        sun_(sun),
        settings_(settings),
        majorant_(model.max_extinction()) {}

  // One path's radiance estimate; vertices and truncation are added to sums.
  glm::dvec3 trace(Rng& rng, ChunkSums& sums) const {
    const double bottom = model_.bottom_radius_km;
    glm::dvec3 position = camera_;
    glm::dvec3 direction = view_;
    glm::dvec3 weight(1.0);
    glm::dvec3 radiance(0.0);
    std::uint64_t collisions = 0;
    for (int order = 0;;) {
      const auto [r, mu] = radius_mu(position, direction);
      const RayInterval interval = atmosphere_interval(model_, r, mu);
      if (!interval.intersects) break;  // Escapes to space: nothing beyond the atmosphere.
      enum class Event { none, rayleigh, mie } event = Event::none;
      double t = interval.start_km;
      while (majorant_ > 0.0) {
        t -= std::log(1.0 - rng.uniform()) / majorant_;
        if (t >= interval.end_km) break;
        if (++collisions > settings_.max_collisions_per_path) {
          ++sums.truncated;
          return radiance;
        }
        const LocalCoefficients k = model_.coefficients(altitude_along_ray(bottom, r, mu, t));
        const glm::dvec3 null = glm::max(glm::dvec3(majorant_) - k.extinction, glm::dvec3(0.0));
        const double p_rayleigh = mean(k.rayleigh_scattering * weight);
        const double p_mie = mean(k.mie_scattering * weight);
        const double p_null = mean(null * weight);
        const double total = p_rayleigh + p_mie + p_null;
        if (!(total > 0.0)) return radiance;  // Weight is zero in every channel.
        const double xi = rng.uniform() * total;
        if (xi < p_rayleigh) {
          weight *= k.rayleigh_scattering * (total / (majorant_ * p_rayleigh));
          event = Event::rayleigh;
          break;
        }
        if (xi < p_rayleigh + p_mie) {
          weight *= k.mie_scattering * (total / (majorant_ * p_mie));
          event = Event::mie;
          break;
        }
        weight *= null * (total / (majorant_ * p_null));
      }

      const int vertex = order + 1;
      if (event == Event::none) {
        // Reached the end of the segment: space, or the ground.
        if (!interval.hits_ground || (order == 0 && !settings_.camera_sees_ground)) break;
        position = glm::normalize(position + interval.end_km * direction) * bottom;
        const glm::dvec3 normal = position / bottom;
        const double cos_sun = glm::dot(normal, sun_);
        if (cos_sun > 0.0) {
          radiance += weight * model_.ground_albedo * (cos_sun / kPi) *
                      transmittance_to_sun(model_, bottom, cos_sun, settings_.shadow_ray);
        }
        ++sums.vertices;
        if (vertex >= settings_.max_order) break;
        weight *= model_.ground_albedo;  // Lambertian BRDF * cos / cosine-weighted pdf.
        const double xi = rng.uniform();
        direction = sample_cosine_hemisphere(normal, xi, rng.uniform());
      } else {
        position += t * direction;
        const double rx = glm::length(position);
        const double nu = glm::dot(direction, sun_);
        const double phase =
            event == Event::rayleigh ? rayleigh_phase(nu) : model_.mie_phase_value(nu);
        radiance +=
            weight * phase *
            transmittance_to_sun(model_, rx, std::clamp(glm::dot(position, sun_) / rx, -1.0, 1.0),
                                 settings_.shadow_ray);
        ++sums.vertices;
        if (vertex >= settings_.max_order) break;
        const double xi = rng.uniform();
        const PhaseSample next = event == Event::rayleigh
                                     ? sample_rayleigh(direction, xi, rng.uniform())
                                     : sample_mie(model_, direction, xi, rng.uniform());
        direction = next.direction;
        weight *= next.weight;
      }
      order = vertex;
      if (order >= settings_.russian_roulette_start_order) {
        const double survive = std::min(1.0, std::max({weight.x, weight.y, weight.z}));
        if (!(survive > 0.0) || rng.uniform() >= survive) break;
        weight /= survive;
      }
    }
    return radiance;
  }

 private:
  const AtmosphereModel& model_;
  glm::dvec3 camera_, view_, sun_;
  const PathTraceSettings& settings_;
  double majorant_;
};

}  // namespace

PathTraceResult path_trace(const AtmosphereModel& model, const glm::dvec3& camera_km,
                           const glm::dvec3& view_dir, const glm::dvec3& sun_dir,
                           const PathTraceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const double bottom = model.bottom_radius_km;
  glm::dvec3 camera = camera_km;
  const double camera_r = glm::length(camera);
  if (camera_r < bottom) {
    camera = camera_r > 0.0 ? camera * (bottom / camera_r) : glm::dvec3(0.0, 0.0, bottom);
  }
  const Tracer tracer(model, camera, glm::normalize(view_dir), glm::normalize(sun_dir), settings);

  const std::uint64_t chunk_size = std::max<std::uint64_t>(settings.chunk_size, 1);
  const std::uint64_t chunks = (settings.samples + chunk_size - 1) / chunk_size;
  std::vector<ChunkSums> sums(chunks);
  std::atomic<std::uint64_t> next{0};
  const auto work = [&] {
    for (std::uint64_t c = next++; c < chunks; c = next++) {
      Rng rng(settings.seed, c);
      const std::uint64_t end = std::min(settings.samples, (c + 1) * chunk_size);
      for (std::uint64_t i = c * chunk_size; i < end; ++i) {
        const glm::dvec3 value = tracer.trace(rng, sums[c]);
        sums[c].sum += value;
        sums[c].sum_sq += value * value;
      }
    }
  };
  const int threads = static_cast<int>(
      std::clamp<std::uint64_t>(static_cast<std::uint64_t>(std::max(settings.threads, 1)), 1,
                                std::max<std::uint64_t>(chunks, 1)));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();

  ChunkSums total;
  for (const ChunkSums& s : sums) {  // Fixed order: bitwise reproducible.
    total.sum += s.sum;
    total.sum_sq += s.sum_sq;
    total.vertices += s.vertices;
    total.truncated += s.truncated;
  }
  PathTraceResult result;
  result.samples = settings.samples;
  if (settings.samples > 0) {
    const double n = static_cast<double>(settings.samples);
    result.radiance = total.sum / n;
    if (settings.samples > 1) {
      const glm::dvec3 variance =
          glm::max((total.sum_sq - total.sum * result.radiance) / (n - 1.0), glm::dvec3(0.0));
      result.ci95 = 1.96 * glm::sqrt(variance / n);
    }
    result.mean_vertices = static_cast<double>(total.vertices) / n;
  }
  result.truncated_paths = total.truncated;
  result.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace welkin::atmosphere::reference
