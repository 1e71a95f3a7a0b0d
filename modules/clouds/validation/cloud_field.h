#pragma once
// The cloud density field of shaders/clouds/density.glsl in double precision, over CPU copies of
// the very noise volumes the GPU generated: what the CPU reference path tracer marches through, so
// that the GPU march and the reference see the same clouds.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "clouds_gpu.h"  // the module's private GPU state (src/)

namespace welkin::clouds {

struct NoiseVolumes {
  int shape_size = 0, detail_size = 0, weather_size = 0;
  std::vector<uint8_t> shape, detail, weather;  // RGBA8 (shape, curl field), R8, RGBA8 as stored
  int systems_size = 0;
  std::vector<uint8_t> systems;  // the weather systems' signal, R8
  int coverage_map_side = 0;
  std::vector<uint8_t> coverage_map;  // the painted coverage map as uploaded (R8, north row first)
};
// Reads the world's noise volumes back (a current GL context; ensure_noise first).
NoiseVolumes read_noise(const CloudsGpu& gpu);

class CloudField {
 public:
  CloudField(NoiseVolumes noise, const FrameBlock& frame, std::vector<LayerBlock> layers);
  // Extinction (1/m) at a camera-relative point, as the march sees it (detail: with the detail noise).
  double extinction(const glm::dvec3& x, bool detail = true) const;
  double altitude(const glm::dvec3& x) const;
  // Distances along a ray from a camera-relative origin to the sphere at `altitude` (near > far: missed).
  glm::dvec2 sphere(const glm::dvec3& origin, const glm::dvec3& dir, double altitude) const;
  double lowest_m() const { return frame_.lowest_m; }
  double highest_m() const { return frame_.highest_m; }
  // The largest extinction anywhere: the sum of the layers' full densities (a majorant).
  double majorant() const;
  // The coverage packed layer `layer` has at x: its own, moved by the weather systems and the painted map.
  double coverage(size_t layer, const glm::dvec3& x) const { return coverage(layers_[layer], x); }
  const FrameBlock& frame() const { return frame_; }

 private:
  double sample(const std::vector<uint8_t>& v, int size, int channels, int channel, glm::dvec3 uvw) const;
  double layer_density(const LayerBlock& L, const glm::dvec3& x, double h, bool detail) const;
  double painted_coverage(const glm::dvec3& x) const;
  double coverage(const LayerBlock& L, const glm::dvec3& x) const;
  NoiseVolumes noise_;
  FrameBlock frame_;
  std::vector<LayerBlock> layers_;
};

}  // namespace welkin::clouds
