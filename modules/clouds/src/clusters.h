#pragma once
// The mesh clusters: puffs placed from the field, lit, sorted and drawn (clusters.cpp).
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

// One puff (std430), declared once in shaders/clouds/puff_block.glsl.h for both languages
// (welkin/gfx/gpu_block.h): written by the placement compute each frame, read by the puffs' draw.
namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "clouds/puff_block.glsl.h"
}  // namespace gpu_blocks
using ClusterPuffGpu = gpu_blocks::ClusterPuff;
static_assert(sizeof(ClusterPuffGpu) == 112, "ClusterPuffGpu: the std430 ClusterPuff struct's size");

// The mesh clusters' GPU state (src/clusters.cpp).
struct ClustersGpu {
  std::unique_ptr<Buffer> proxy;  // the puff's proxy mesh as a triangle list of vec4 (pulled by gl_VertexID)
  int proxy_vertices = 0, proxy_level = -1;
  PlacementBuffers placement;
  std::unique_ptr<Buffer> puffs, order;
  size_t puff_capacity = 0, order_capacity = 0;
  GLuint vao = 0;
  int puff_count = 0;  // instances drawn last frame (clusters x puffs)
  ~ClustersGpu();
};

// Render phase, after the god rays and before the march (order 145): the mesh clusters, placed from
// the field, lit, sorted and drawn over the frame; the march then stops where they turn opaque.
void clusters_system(SystemContext& sc);
// The proxy mesh of one puff: a cube refined by Catmull-Clark (OpenSubdiv) onto the unit sphere and
// pushed out until it encloses it, as a triangle list (counter-clockwise from outside).
std::vector<glm::vec4> puff_proxy_mesh(int level);

}  // namespace welkin::clouds
