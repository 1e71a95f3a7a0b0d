#pragma once
// CPU side of a terrain: the glTF model flattened into the scene's z-up frame, split into chunks,
// each with simplified levels of detail whose chunk borders are locked (so neighbours at different
// levels still meet without cracks).
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "welkin/assets/model.h"
#include "welkin/terrain/components.h"

namespace welkin::terrain {

struct LodRange {
  uint32_t first_index = 0, index_count = 0;
  float error_m = 0.0f;  // geometric error of this level against the full mesh, in metres
};

struct Chunk {
  glm::vec3 min{0.0f}, max{0.0f};  // bounds in the model's z-up frame
  int material = -1;
  std::vector<LodRange> lods;      // lods[0] is the full mesh
};

struct TerrainMesh {
  std::vector<glm::vec3> positions, normals;  // z-up, metres from the model origin
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;              // all chunks and levels, one buffer
  std::vector<Chunk> chunks;
  glm::vec3 min{0.0f}, max{0.0f};
  size_t full_triangles = 0;
};

// glTF (y-up) to scene (z-up): x = X, y = -Z, z = Y.
glm::vec3 gltf_to_scene(const glm::vec3& p);

TerrainMesh build_terrain_mesh(const assets::Model& model, const Terrain& settings);

// The finest level whose projected error stays within `pixel_error` for a chunk at `distance_m`
// seen by a camera with `pixels_per_radian` (height / vertical field of view); coarser when far.
int select_lod(const Chunk& chunk, double distance_m, double pixels_per_radian, double pixel_error);

}  // namespace welkin::terrain
