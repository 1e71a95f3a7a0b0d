#pragma once
// The clouds' shadow cascades: beer shadow maps across the sun's direction, nearest first, which
// every material reads through the light environment (light_term.cpp).
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "frame_block.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// The light term's CloudsShadow block (std140), declared once in shaders/clouds/shadow_block.glsl.h
// for both languages (welkin/gfx/gpu_block.h): one plane per cascade, nearest first.
namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "clouds/shadow_block.glsl.h"
}  // namespace gpu_blocks
using ShadowBlock = gpu_blocks::CloudsShadowGpu;
inline constexpr int kMaxShadowCascades = 4;
static_assert(sizeof(ShadowBlock::cascades) / sizeof(ShadowBlock::cascades[0]) == kMaxShadowCascades);
static_assert(sizeof(ShadowBlock) == 240, "ShadowBlock: the std140 CloudsShadow block's size");

// What the shadow map was made from; a frame whose key is not stale reuses it.
struct ShadowKey {
  bool wanted = false;
  glm::vec3 sun{0.0f};
  double time_s = 0.0;
  glm::dvec3 anchor_m{0.0};  // the camera when the map was made: the map's centre
  float texel_m = 1.0f, max_wind_mps = 0.0f;
  int size = 0;
  std::vector<float> settings;  // the layers' and medium's values the map depends on
  // Stale when the sun turned by more than ~0.05 degrees, the settings changed, the wind moved the
  // clouds by half a texel, or the camera left the middle half of the map.
  bool stale(const ShadowKey& now) const {
    return glm::dot(sun, now.sun) < 0.9999996f || settings != now.settings || size != now.size ||
           std::abs(now.time_s - time_s) * max_wind_mps > 0.5 * texel_m ||
           glm::length(now.anchor_m - anchor_m) > 0.125 * texel_m * size;
  }
};

struct CloudsGpu;
// Places this frame's cascades (gpu.shadow) and marks those whose key went stale for a rebuild.
void place_shadow_cascades(CloudsGpu& gpu, const VolumetricClouds& clouds, const CloudsContext& ctx,
                           const PackedLayers& layers, const FrameBlock& block, const FrameView& view);
// Render phase, before the geometry (order -50): noise when the seed changed, this frame's block and
// layers, and the shadow map every material reads.
void shadow_system(SystemContext& sc);

}  // namespace welkin::clouds
