#pragma once
// CPU side of a terrain: the glTF model flattened into the scene's z-up frame, split into chunks,
// each with simplified levels of detail whose chunk borders are locked (so neighbours at different
// levels still meet without cracks).
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "welkin/assets/model.h"
#include "welkin/terrain/components.h"

namespace welkin::terrain {

struct LodRange {
  uint32_t first_index = 0, index_count = 0;
  float error_m = 0.0f;  // geometric error of this level against the full mesh, in metres
  uint32_t vertex_count = 0;  // the level uses the chunk's first vertex_count vertices, and only those
};

struct Chunk {
  glm::vec3 min{0.0f}, max{0.0f};  // bounds in the model's z-up frame
  int material = -1;
  uint32_t base_vertex = 0;        // the chunk's own vertices start here; its indices count from it
  std::vector<LodRange> lods;      // lods[0] is the full mesh
};

// A chunk holds at most this many vertices (its indices are 16-bit); a cell with more is split.
inline constexpr size_t kMaxChunkVertices = 65536;

// Signed normalized 10-10-10-2 (GL_INT_2_10_10_10_REV): x in the low bits, 1/511 steps (0.1 degree).
uint32_t pack_normal(const glm::vec3& n);
glm::vec3 unpack_normal(uint32_t packed);

struct TerrainMesh {
  // Each chunk's vertices together (a vertex on a chunk border is in each chunk that uses it), so that
  // indices fit in 16 bits: half the bytes of 32-bit ones, and normals in 4 bytes instead of 12.
  std::vector<glm::vec3> positions;  // z-up, metres from the model origin
  std::vector<uint32_t> normals;     // pack_normal
  std::vector<glm::vec2> uvs;
  std::vector<uint16_t> indices;     // all chunks and levels, one buffer; each from its chunk's base_vertex
  std::vector<Chunk> chunks;
  glm::vec3 min{0.0f}, max{0.0f};
  size_t full_triangles = 0;
};

// glTF (y-up) to scene (z-up): x = X, y = -Z, z = Y.
glm::vec3 gltf_to_scene(const glm::vec3& p);

TerrainMesh build_terrain_mesh(const assets::Model& model, const Terrain& settings);

// The built mesh in the disk cache (welkin/core/disk_cache.h): what it depends on is the file's
// bytes (Model::content_hash, read without decoding its geometry) and the build settings, so a start
// that finds it neither decodes the geometry (Draco) nor refines or simplifies it. Bump
// kMeshCacheVersion when what build_terrain_mesh makes changes: its own code, or the loader's
// conversion or refinement (assets) that it builds on.
inline constexpr int kMeshCacheVersion = 4;
std::string mesh_cache_key(uint64_t content_hash, const Terrain& settings);
// Two entries: the counts (fixed size), then the arrays and chunks they size.
std::string mesh_counts_bytes(const TerrainMesh& mesh);
std::string mesh_body_bytes(const TerrainMesh& mesh);
// The size of the body the counts describe; nullopt when they are not counts of a mesh (a damaged or
// foreign entry) or would exceed max_bytes.
std::optional<size_t> mesh_body_size(std::span<const uint8_t> counts, size_t max_bytes);
// A mesh's vertex and index arrays as bytes, for upload: a built mesh's vectors, or ranges of a body
// read from the cache (read in place, never copied into vectors).
struct MeshArrays {
  std::span<const uint8_t> positions, normals, uvs, indices;
};
MeshArrays mesh_arrays(const TerrainMesh& mesh);
// The mesh's chunks and bounds back, its arrays left empty and found in `body` (`arrays`); nullopt
// unless every range is consistent: the chunks' levels inside the indices and every index inside the
// vertices (the cache folder is input like any other).
std::optional<TerrainMesh> mesh_from_bytes(std::span<const uint8_t> counts, std::span<const uint8_t> body,
                                           MeshArrays& arrays);

// The finest level whose projected error stays within `pixel_error` for a chunk at `distance_m`
// seen by a camera with `pixels_per_radian` (height / vertical field of view); coarser when far.
int select_lod(const Chunk& chunk, double distance_m, double pixels_per_radian, double pixel_error);

}  // namespace welkin::terrain
