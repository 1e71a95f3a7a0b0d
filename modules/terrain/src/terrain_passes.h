#pragma once
// What the terrain's passes draw (terrain_system.cpp decides, per frame) and the passes' GL work
// (terrain_passes.cpp): the shadow cascades, the kept terrain of a still view, the surface and its light.
#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "terrain_gpu.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/renderer.h"

namespace welkin {
class World;
}

namespace welkin::terrain {

struct Draw {
  uint32_t first, count;
  int material;
  uint32_t base_vertex;
  uint32_t vertex_count;  // the level's vertices: the first of its chunk's
};

// A chunk that casts shadows, with its camera-relative bounds (culled against each cascade).
struct Caster {
  size_t chunk;
  glm::vec3 lo, hi;
};

struct Placed {
  GpuTerrain* gpu;
  glm::dvec3 anchor_m;  // model origin in the scene frame
  glm::mat3 rotation;   // heading
  float inverse_two_radius;
  std::vector<Draw> draws;
  float lod_pixel_error;
  std::vector<Caster> casters;                    // every chunk (casters outside the view still cast)
  std::array<std::vector<Draw>, 3> shadow_draws;  // per cascade: the casters it sees, at its level
  size_t triangles = 0;
};

// The cascades of `stale` drawn into the atlas (each of its casters' shadow draws), and each recorded
// as drawn from its `inputs`.
void draw_shadow_cascades(const Texture& atlas, const std::vector<Placed>& placed,
                          const std::array<glm::mat4, kShadowCascades>& light_view_projection, int size,
                          const std::vector<int>& stale,
                          const std::array<std::string, kShadowCascades>& inputs, RenderContext& rc,
                          TerrainCache& cache);
// A still view: the kept depth replaces the frame's, the kept colour goes where it holds terrain.
void draw_kept_terrain(const Texture& color, const Texture& depth, RenderContext& rc,
                       const TerrainCache& cache);
// What the view's terrain looks like where it is drawn (the pixels `covered`): each material's inputs
// per pixel into `surface`, with the depth, and the materials' own light into the colour (`emissive`).
struct SurfaceDraw {
  PixelRect covered;
  bool emissive = false, own_transforms = false;
};
void draw_surface(const Texture& color, const Texture& surface, const Texture& depth,
                  const std::vector<Placed>& placed, const SurfaceDraw& s, RenderContext& rc);
// The surface's light, once per pixel (the runtime's shading), and the frame kept when it was drawn
// twice alike (`inputs`: what it was drawn from, none when that cannot be said).
void draw_surface_light(const Texture& color, const Texture& depth, const Texture& surface,
                        const SurfaceDraw& s, const std::optional<uint64_t>& inputs, RenderContext& rc,
                        World& world, TerrainCache& cache);

}  // namespace welkin::terrain
