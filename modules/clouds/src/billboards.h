#pragma once
// The billboards: the mid- and far-range clouds as baked views of archetypes (billboards.cpp).
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "placement.h"
#include "welkin/gfx/gpu_block.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// One billboard (std430), declared once in shaders/clouds/billboard_block.glsl.h for both languages
// (welkin/gfx/gpu_block.h): written by the placement compute each frame, read by the billboards' draw.
namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "clouds/billboard_block.glsl.h"
}  // namespace gpu_blocks
using BillboardGpu = gpu_blocks::Billboard;
static_assert(sizeof(BillboardGpu) == 80, "BillboardGpu: the std430 Billboard struct's size");

// What an atlas was baked from: a frame whose key equals it reuses the atlas.
struct BillboardBakeKey {
  std::vector<float> values;
  bool operator==(const BillboardBakeKey&) const = default;
};

// The billboards' GPU state (src/billboards.cpp).
struct BillboardsGpu {
  std::unique_ptr<Texture> volume, atlas;  // the archetypes' extinction, and their views
  std::unique_ptr<Buffer> archetypes;      // each archetype's place in the noise and its weather's score
  // The fill the light model reads beside each (r8): per voxel, and per texel averaged along the view.
  std::unique_ptr<Texture> fill_volume, fill_atlas;
  PlacementBuffers placement;
  std::unique_ptr<Buffer> billboards, order;
  size_t billboard_capacity = 0, order_capacity = 0;
  BillboardBakeKey baked;  // what the atlas holds (empty: nothing yet)
  int bakes = 0;           // how often it was baked (tests, stats)
  GLuint vao = 0;
  int drawn = 0;  // instance slots drawn last frame
  ~BillboardsGpu();
};

// Render phase, before the mesh clusters (order 144): the billboards, baked when their key changed,
// placed, lit, sorted and drawn into the mid- and far-range clouds' targets.
void billboards_system(SystemContext& sc);

}  // namespace welkin::clouds
