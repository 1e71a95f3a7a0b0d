#pragma once
// GPU copies of terrain meshes and their material textures, owned by the world and shared by every
// entity that shows the same file with the same build settings.
#include <map>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "terrain_mesh.h"
#include "welkin/assets/asset_cache.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/gpu_block.h"

namespace welkin::terrain {

struct GpuMaterial {
  glm::vec4 base_color_factor{1.0f};
  float metallic = 0.0f, roughness = 1.0f;
  glm::vec3 emissive{0.0f};
  GlTextureName base_color, metallic_roughness, normal, occlusion, emissive_map;
  float occlusion_strength = 1.0f;  // glTF: occlusion = 1 + strength (texel - 1)
  // Each texture's KHR_texture_transform: base colour, metallic-roughness, occlusion, emissive.
  std::array<glm::mat3, 4> uv_transforms{glm::mat3(1.0f), glm::mat3(1.0f), glm::mat3(1.0f), glm::mat3(1.0f)};
  // A texture it has whose transform is not the base colour's (the surface shader then computes each).
  bool own_transforms() const {
    const bool present[4] = {bool(base_color), bool(metallic_roughness), bool(occlusion), bool(emissive_map)};
    for (int i = 1; i < 4; ++i)
      if (present[i] && uv_transforms[size_t(i)] != uv_transforms[0]) return true;
    return false;
  }
};

struct GpuTerrain {
  TerrainMesh mesh;
  GlBufferName positions, normals, uvs, indices;
  GlVertexArrayName vao;
  std::vector<GpuMaterial> materials;  // indexed like the glTF's materials; the last is the default
};

inline constexpr int kShadowCascades = 3;

// The light term's TerrainCascades block (std140), declared once in shaders/terrain/cascades_block.glsl.h
// for both languages (welkin/gfx/gpu_block.h).
namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "terrain/cascades_block.glsl.h"
}  // namespace gpu_blocks
using CascadesBlock = gpu_blocks::TerrainCascadesGpu;
static_assert(sizeof(CascadesBlock::cascades) / sizeof(CascadesBlock::cascades[0]) == kShadowCascades);
static_assert(sizeof(CascadesBlock) == 256, "CascadesBlock: the std140 TerrainCascades block's size");

struct TerrainCache {
  static constexpr std::string_view kTypeName = "terrain.TerrainCache";
  // Cascades side by side in one depth atlas (kShadowCascades x 1), compared in the shader.
  std::unique_ptr<Texture> shadow_atlas;
  Texture& shadow_map(int cascade_size);
  // What each cascade's depths were last drawn from (terrain_system.cpp, cascade_inputs): a cascade
  // whose inputs are the same is not drawn again.
  std::array<std::string, kShadowCascades> cascade_inputs;
  // Where the last frame's cascades were (scene frame) and their sides: a cascade stays there while its
  // slice of the view stays inside it (make_cascades).
  struct CascadePlaces {
    std::array<glm::dvec3, kShadowCascades> centre_m{};
    std::array<float, kShadowCascades> extent_m{};
  };
  std::optional<CascadePlaces> cascade_places;
  size_t cascade_draws = 0;  // cascades drawn (tests, stats)
  // This frame's cascades as the light term's std140 block (terrain/light_term.glsl), and its buffer.
  CascadesBlock cascade_block{};
  std::unique_ptr<Buffer> cascade_buffer;
  // The view's terrain as last drawn (terrain_system.cpp, view_inputs): its colour and depth, and
  // the digest of what they were drawn from. A frame whose digest is the same takes them instead of
  // drawing; they are made once a view is drawn twice alike, so a moving view never copies them.
  std::unique_ptr<Texture> kept_color, kept_depth;
  uint64_t kept_inputs = 0, drawn_inputs = 0;
  size_t view_draws = 0;  // frames whose terrain was drawn rather than kept (tests, stats)
  assets::AssetCache assets;
  // With the disk cache on: the file read for its materials and images only, and (only when the built
  // mesh is not on disk) again whole (`assets`).
  assets::AssetCache assets_without_geometry{assets::LoadOptions{.decode_meshes = false}};
  // With the disk cache on and images compressed: the file read for its materials and its images'
  // hashes only, the compressed levels coming from the disk cache (images decoded only on a miss).
  assets::AssetCache assets_bare{assets::LoadOptions{.decode_images = false, .decode_meshes = false}};
  std::map<std::string, std::unique_ptr<GpuTerrain>> terrains;  // key: file + build settings
  size_t mesh_cache_reads = 0;  // meshes read from the disk cache instead of built (tests)
  size_t image_cache_reads = 0;  // compressed images read from the disk cache instead of made (tests)
  // Loads (or returns) the GPU terrain for these settings; throws welkin::Error naming the file.
  GpuTerrain& get(const Terrain& settings);

 private:
  // The built mesh (from the disk cache when it holds it: `body`, its arrays read in place), its arrays
  // as bytes, and the model its materials come from.
  struct LoadedMesh {
    std::shared_ptr<const assets::Model> model;
    std::vector<uint8_t> body;
    MeshArrays arrays;
  };
  LoadedMesh load_mesh(const Terrain& settings, TerrainMesh& mesh);
  std::vector<GpuMaterial> upload_materials(const Terrain& settings, const assets::Model& model);
};

}  // namespace welkin::terrain
