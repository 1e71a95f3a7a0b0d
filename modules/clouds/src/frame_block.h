#pragma once
// What the cloud shaders see of a frame: the frame block and the packed layers every cloud shader
// reads (shaders/clouds/density.glsl), made by frame_block.cpp.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "noise_volumes.h"
#include "welkin/clouds/components.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gpu_block.h"

namespace welkin::clouds {

// The frame block (std140) and a packed layer (std430), declared once in shaders/clouds/blocks.glsl.h
// for both languages (welkin/gfx/gpu_block.h).
namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "clouds/blocks.glsl.h"
}  // namespace gpu_blocks
using FrameBlock = gpu_blocks::CloudsFrameGpu;
using LayerBlock = gpu_blocks::CloudLayerGpu;
static_assert(sizeof(FrameBlock) == 368, "FrameBlock: the std140 CloudsFrame block's size");
static_assert(sizeof(LayerBlock) == 160, "LayerBlock: the std430 CloudLayerGpu struct's size");

// Where the planet is and when it is: what the clouds read of other modules (through reflection).
struct CloudsContext {
  double planet_radius_m = 6360000.0;
  glm::dvec3 planet_center_m{0.0, 0.0, -6360000.0};
  double time_s = 0.0;               // drives the wind: the time of day when there is one
  glm::vec3 sun_direction{0, 0, 1};  // toward the sun
  bool sun_up_for_clouds = true;     // the sun still lights cloud tops (else the moon is marched)
  // The painted coverage map, when the scene has one: the most it adds to a layer's coverage
  // ((largest texel - 128) / 127, below 0 when it only clears) and its revision.
  bool has_coverage_map = false;
  float coverage_map_raise = 0.0f;
  uint64_t coverage_map_revision = 0;
};
// A layer's coverage c where the weather systems' signal is g (uniform on [0, 1]): raised where
// g > 0.5 and lowered where g < 0.5 by up to amount x 4 c (1 - c), so that 0 and 1 stay clear and
// overcast and the planet's mean stays c.
inline double system_coverage(double c, double g, double amount) {
  const double v = c + amount * (2.0 * g - 1.0) * 4.0 * c * (1.0 - c);
  return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

// Coverage a painted map texel adds (128 nothing, 255 +1, 0 about -1).
inline double painted_coverage_offset(double texel) {
  return (texel - 128.0) / 127.0;
}

inline constexpr int kMaxBands = 4;
// The layers' altitude ranges merged into at most kMaxBands disjoint bands (closest gaps closed first).
std::vector<glm::vec2> altitude_bands(std::vector<glm::vec2> ranges, int max_bands = kMaxBands);

// The layers that can hold cloud this frame (visible, soloed when any is, coverage, thickness and
// density above zero), packed.
struct PackedLayers {
  std::vector<LayerBlock> layers;
  std::vector<glm::vec2> ranges;  // each packed layer's altitude range, its base's variation included
  std::vector<int> source_index;  // the component's layer index of each packed layer
  float lowest_m = 0.0f, highest_m = 0.0f;
  float lowest_shadow_m = 0.0f, highest_shadow_m = 0.0f;
  bool any_shadow = false;
  // The layers that cast no shadow and lie wholly above every layer that does (decks_over_casters).
  float lowest_deck_m = 1.0f, highest_deck_m = 0.0f;
};
PackedLayers pack_layers(const VolumetricClouds& clouds, const CloudsContext& context,
                         const glm::dvec3& camera_m);
FrameBlock make_frame_block(const VolumetricClouds& clouds, const CloudsContext& context,
                            const NoiseFacts& noise, const FrameView& view, const PackedLayers& layers,
                            int march_width, int march_height, uint64_t frame_index);
// The shape model of a genus: dome (0 sheet .. 1 dome), weather frequency relative to the period, and
// its erosion (welkin/clouds/genera.h).
struct GenusModel {
  float dome;
  float weather_frequency;
  float billow, wisp, edge;
  float streak, hook_s, anvil_start, anvil_spread;
};
GenusModel genus_model(Genus genus);

}  // namespace welkin::clouds
