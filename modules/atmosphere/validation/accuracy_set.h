// The fixed set of view rays `welkin accuracy atmosphere` sweeps, and the file that caches their
// path-traced references. No GL and no runtime: the references can be computed anywhere.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "reference/atmosphere_model.h"
#include "reference/probe.h"

namespace welkin::atmosphere {

// Altitudes 0, 1 and 10 km; sun elevations -6 (civil twilight), 0, 3, 10, 30, 60 and 90 degrees; view
// elevations 2, 5, 10, 30, 60 and 90 degrees at azimuths 0, 45, 90 and 180 degrees from the sun's (one
// azimuth where the view or the sun is at the zenith): 396 rays. Then the same grid with the sun 3
// degrees below the horizon (63 rays), and 10 rays from the ground with the sun 12 degrees below it
// (nautical twilight; views 2, 10, 30 and 90 degrees up at azimuths 0, 90 and 180): 469 rays. The
// sun's azimuth is 0.
std::vector<reference::ProbeGeometry> accuracy_rays();

// Path tracing of the cached references: seeded, so a rerun reproduces them bit for bit. With the sun
// below the horizon only paths that climb into the sunlit air score, so those rays get 16 times the
// paths (95% intervals of up to 15% at 2^20, 4% at 2^24), and 128 times with the sun 9 degrees or
// more below it, where the sunlit air lies above the whole atmosphere overhead (60-100% at 2^22).
struct ReferenceSettings {
  std::uint64_t samples = 1u << 20;
  std::uint64_t samples_sun_below_horizon = 1u << 24;
  std::uint64_t samples_deep_twilight = 1u << 27;
  std::uint64_t seed = 20261123;
  std::uint64_t chunk_size = 512;  // part of the result's identity (reference/path_tracer.h)

  std::uint64_t samples_for(const reference::ProbeGeometry& g) const {
    return g.sun_zenith_deg >= 99.0 ? samples_deep_twilight
           : g.sun_zenith_deg > 90.0 ? samples_sun_below_horizon
                                     : samples;
  }
};

struct CachedReference {
  glm::dvec3 radiance{0.0};  // all orders, 1/sr for sun illuminance 1
  glm::dvec3 ci95{0.0};      // 95% confidence half-width
};

// References keyed by geometry, valid for one reference model and one ReferenceSettings: a file made
// for another model, seed or chunking is ignored rather than trusted, and an entry whose sample count
// differs from what the settings give its ray is dropped (and traced again).
class ReferenceCache {
 public:
  ReferenceCache(const reference::AtmosphereModel& model, const ReferenceSettings& settings);
  // Reads `path` if it exists and matches; returns how many references it held (0 if it did not match).
  std::size_t load(const std::string& path);
  // Writes every reference through a temporary file and a rename.
  void save(const std::string& path) const;
  std::optional<CachedReference> find(const reference::ProbeGeometry& g) const;
  void put(const reference::ProbeGeometry& g, const CachedReference& value);
  std::size_t size() const { return entries_.size(); }
  const ReferenceSettings& settings() const { return settings_; }

 private:
  std::string model_key_;
  ReferenceSettings settings_;
  std::map<std::string, std::pair<reference::ProbeGeometry, CachedReference>> entries_;
};

// All-orders radiance of one ray as the cache stores it (camera sees the lit ground).
CachedReference path_trace_reference(const reference::AtmosphereModel& model,
                                     const reference::ProbeGeometry& g, const ReferenceSettings& settings,
                                     int threads);

}  // namespace welkin::atmosphere
