#include "terrain_mesh.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "welkin/assets/subdivision.h"
#include "welkin/core/error.h"

namespace welkin::terrain {

glm::vec3 gltf_to_scene(const glm::vec3& p) { return {p.x, -p.z, p.y}; }

namespace {

// UVs for refined geometry (OpenSubdiv gives positions and normals only): the affine map from
// ground position to UV fitted by least squares over the original vertices. Terrains are textured
// by planar projection, so this reproduces their UVs; other meshes get a sensible planar mapping.
glm::mat3x2 fit_planar_uv(const std::vector<glm::vec3>& p, const std::vector<glm::vec2>& uv) {
  glm::dmat3 ata(0.0);
  glm::dmat3x2 atb(0.0);
  for (size_t i = 0; i < p.size() && i < uv.size(); ++i) {
    glm::dvec3 a(p[i].x, p[i].y, 1.0);
    ata += glm::outerProduct(a, a);
    atb += glm::outerProduct(glm::dvec2(uv[i]), a);
  }
  if (std::abs(glm::determinant(ata)) < 1e-12) return glm::mat3x2(0.0f);
  return glm::mat3x2(atb * glm::inverse(ata));
}

struct Flat {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
  int material = -1;
};

// One primitive instance in scene coordinates (node transform and the axis change applied).
Flat flatten(const assets::Primitive& prim, const glm::mat4& node_world, const Terrain& s) {
  Flat f;
  f.material = prim.material;
  glm::mat3 normal_m = glm::transpose(glm::inverse(glm::mat3(node_world)));
  f.positions.reserve(prim.positions.size());
  for (size_t i = 0; i < prim.positions.size(); ++i) {
    f.positions.push_back(gltf_to_scene(glm::vec3(node_world * glm::vec4(prim.positions[i], 1.0f))));
    f.normals.push_back(glm::normalize(gltf_to_scene(normal_m * prim.normals[i])));
  }
  f.uvs = prim.uv0;
  if (f.uvs.size() != f.positions.size()) f.uvs.assign(f.positions.size(), glm::vec2(0.0f));
  f.indices = prim.indices;
  if (s.refine && s.refine_levels > 0) {
    assets::ControlMesh cm{f.positions, std::vector<int>(f.indices.size() / 3, 3),
                           std::vector<int>(f.indices.begin(), f.indices.end())};
    assets::RefineSettings rs{.levels = s.refine_levels, .max_triangles = size_t(s.refine_max_triangles)};
    assets::RefinedMesh r = assets::refine(cm, rs);
    glm::mat3x2 uv_map = fit_planar_uv(f.positions, f.uvs);
    f.uvs.clear();
    for (const auto& p : r.positions) f.uvs.push_back(uv_map * glm::vec3(p.x, p.y, 1.0f));
    f.positions = std::move(r.positions);
    f.normals = std::move(r.normals);
    f.indices = std::move(r.indices);
  }
  return f;
}

}  // namespace

uint32_t pack_normal(const glm::vec3& n) {
  auto q = [](float v) {
    return uint32_t(int32_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f))) & 0x3FFu;
  };
  return q(n.x) | q(n.y) << 10 | q(n.z) << 20;
}

glm::vec3 unpack_normal(uint32_t p) {
  // Sign-extended from 10 bits, then as GL normalizes signed values: max(c / 511, -1).
  auto f = [](uint32_t bits) { return std::max(float(int32_t(bits << 22) >> 22) / 511.0f, -1.0f); };
  return {f(p), f(p >> 10), f(p >> 20)};
}

TerrainMesh build_terrain_mesh(const assets::Model& model, const Terrain& s) {
  TerrainMesh out;
  out.min = glm::vec3(INFINITY);
  out.max = glm::vec3(-INFINITY);
  const int n = std::max(1, s.chunks_per_side);
  for (const assets::Node& node : model.nodes) {
    if (node.mesh < 0) continue;
    for (const assets::Primitive& prim : model.meshes[size_t(node.mesh)].primitives) {
      Flat f = flatten(prim, node.world, s);
      if (f.indices.empty()) continue;
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (const auto& p : f.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
      out.min = glm::min(out.min, lo);
      out.max = glm::max(out.max, hi);
      out.full_triangles += f.indices.size() / 3;
      // Bucket triangles by centroid on an n x n grid over the primitive's ground footprint.
      std::vector<std::vector<uint32_t>> buckets(size_t(n) * n);
      glm::vec2 extent = glm::max(glm::vec2(hi - lo), glm::vec2(1e-3f));
      for (size_t t = 0; t + 2 < f.indices.size(); t += 3) {
        glm::vec3 c =
            (f.positions[f.indices[t]] + f.positions[f.indices[t + 1]] + f.positions[f.indices[t + 2]]) /
            3.0f;
        int cx = std::clamp(int((c.x - lo.x) / extent.x * n), 0, n - 1);
        int cy = std::clamp(int((c.y - lo.y) / extent.y * n), 0, n - 1);
        auto& b = buckets[size_t(cy) * n + cx];
        b.insert(b.end(), {f.indices[t], f.indices[t + 1], f.indices[t + 2]});
      }
      // Each chunk is simplified on its own compact vertex set (cost proportional to the chunk), which
      // is also what it draws from. A cell whose triangles use more than kMaxChunkVertices vertices is
      // split into chunks of consecutive triangles.
      std::vector<int32_t> to_local(f.positions.size(), -1);
      for (const auto& b : buckets)
        for (size_t start = 0; start < b.size();) {
          std::vector<uint32_t> global;
          std::vector<glm::vec3> local_pos;
          std::vector<uint32_t> local_idx;
          Chunk chunk;
          chunk.material = f.material;
          chunk.min = glm::vec3(INFINITY);
          chunk.max = glm::vec3(-INFINITY);
          size_t end = start;
          for (; end < b.size() && global.size() + 3 <= kMaxChunkVertices; end += 3)
            for (size_t k = end; k < end + 3; ++k) {
              const uint32_t i = b[k];
              if (to_local[i] < 0) {
                to_local[i] = int32_t(global.size());
                global.push_back(i);
                local_pos.push_back(f.positions[i]);
              }
              local_idx.push_back(uint32_t(to_local[i]));
              chunk.min = glm::min(chunk.min, f.positions[i]),
              chunk.max = glm::max(chunk.max, f.positions[i]);
            }
          start = end;
          for (uint32_t g : global) to_local[g] = -1;
          // meshopt reports error relative to the extent of the vertices it was given.
          const float scale = meshopt_simplifyScale(&local_pos[0].x, local_pos.size(), sizeof(glm::vec3));
          std::vector<std::vector<uint32_t>> levels{local_idx};
          std::vector<float> errors{0.0f};
          for (int l = 1; l < std::max(1, s.lod_levels); ++l) {
            const std::vector<uint32_t>& finer = levels.back();
            std::vector<uint32_t> coarser(finer.size());
            size_t target = std::max<size_t>(3, finer.size() / 4 / 3 * 3);
            float error = 0.0f;
            // Borders locked: the chunk's outline stays identical at every level, so no cracks.
            coarser.resize(meshopt_simplify(coarser.data(), finer.data(), finer.size(), &local_pos[0].x,
                                            local_pos.size(), sizeof(glm::vec3), target, 1.0f,
                                            meshopt_SimplifyLockBorder, &error));
            if (coarser.size() >= finer.size()) break;  // nothing left to remove
            levels.push_back(std::move(coarser));
            errors.push_back(std::max(error * scale, errors.back()));
          }
          // Triangles ordered for vertex reuse; vertices in the order the coarsest level first uses
          // them, then those each finer level adds (a coarser level's are a subset of a finer one's).
          // Each level then draws from a prefix of the chunk's vertices, and a rasteriser that shades
          // a draw's whole index range (llvmpipe does) shades only those: the coarsest levels of the
          // far chunks had shaded all of their chunk's vertices, 11 ms of the demo's 12 ms terrain floor.
          for (auto& level : levels)
            meshopt_optimizeVertexCache(level.data(), level.data(), level.size(), local_pos.size());
          std::vector<uint32_t> coarse_first;
          for (auto level = levels.rbegin(); level != levels.rend(); ++level)
            coarse_first.insert(coarse_first.end(), level->begin(), level->end());
          std::vector<uint32_t> remap(local_pos.size());
          meshopt_optimizeVertexFetchRemap(remap.data(), coarse_first.data(), coarse_first.size(),
                                           local_pos.size());
          std::vector<uint32_t> ordered(global.size());
          for (size_t i = 0; i < global.size(); ++i)
            ordered[remap[i]] = global[i];  // every vertex is in level 0
          chunk.base_vertex = uint32_t(out.positions.size());
          for (uint32_t g : ordered)
            out.positions.push_back(f.positions[g]), out.normals.push_back(pack_normal(f.normals[g])),
                out.uvs.push_back(f.uvs[g]);
          for (size_t l = 0; l < levels.size(); ++l) {
            uint32_t used = 0;
            for (uint32_t i : levels[l]) used = std::max(used, remap[i] + 1);
            chunk.lods.push_back(
                LodRange{uint32_t(out.indices.size()), uint32_t(levels[l].size()), errors[l], used});
            for (uint32_t i : levels[l]) out.indices.push_back(uint16_t(remap[i]));
          }
          out.chunks.push_back(std::move(chunk));
        }
    }
  }
  if (out.positions.empty())
    throw Error(ErrorInfo{.file = model.file, .message = "the model has no triangles to draw"});
  return out;
}

int select_lod(const Chunk& chunk, double distance_m, double pixels_per_radian, double pixel_error) {
  int chosen = 0;
  for (int l = 1; l < int(chunk.lods.size()); ++l)
    if (chunk.lods[size_t(l)].error_m / std::max(distance_m, 1e-3) * pixels_per_radian <= pixel_error)
      chosen = l;
  return chosen;
}

namespace {

// Counts in the cache's counts entry, in this order.
enum CountIndex { kVertices, kIndices, kChunks, kLods, kCountFields };
struct ChunkRecord {
  glm::vec3 min, max;
  int32_t material;
  uint32_t lods;
  uint32_t base_vertex;
};
struct LodRecord {
  uint32_t first_index, index_count;
  float error_m;
};
struct MeshRecord {
  glm::vec3 min, max;
  uint64_t full_triangles;
};
static_assert(sizeof(ChunkRecord) == 36 && sizeof(LodRecord) == 12 && sizeof(MeshRecord) == 32);

// A vertex's bytes in the body: position, packed normal, uv.
constexpr size_t kVertexBytes = sizeof(glm::vec3) + sizeof(uint32_t) + sizeof(glm::vec2);

template <class T> void append(std::string& out, const T* data, size_t count) {
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

// Reads `count` values of T at `at`, advancing it; the caller has checked the sizes.
template <class T> std::vector<T> take(std::span<const uint8_t> bytes, size_t& at, size_t count) {
  std::vector<T> v(count);
  if (count) std::memcpy(v.data(), bytes.data() + at, count * sizeof(T));
  at += count * sizeof(T);
  return v;
}

std::optional<size_t> body_size(const uint64_t (&c)[kCountFields], size_t max_bytes) {
  // Each count alone within the limit first, so that the sum (at most 4 limits) cannot overflow.
  const uint64_t limit = std::min<uint64_t>(max_bytes, uint64_t(1) << 60);
  if (c[kVertices] > limit / kVertexBytes || c[kIndices] > limit / sizeof(uint16_t) ||
      c[kChunks] > limit / sizeof(ChunkRecord) || c[kLods] > limit / sizeof(LodRecord))
    return std::nullopt;
  const uint64_t size = c[kVertices] * kVertexBytes + c[kIndices] * sizeof(uint16_t) +
                        c[kChunks] * sizeof(ChunkRecord) + c[kLods] * sizeof(LodRecord) + sizeof(MeshRecord);
  if (size > limit) return std::nullopt;
  return size_t(size);
}

bool read_counts(std::span<const uint8_t> bytes, uint64_t (&c)[kCountFields]) {
  if (bytes.size() != sizeof(c)) return false;
  std::memcpy(c, bytes.data(), sizeof(c));
  return true;
}

}  // namespace

std::string mesh_cache_key(uint64_t content_hash, const Terrain& s) {
  return "welkin terrain: mesh, version " + std::to_string(kMeshCacheVersion) + ", meshoptimizer " +
         std::to_string(MESHOPTIMIZER_VERSION) + "\nfile " + std::to_string(content_hash) +
         "\nchunks per side " + std::to_string(s.chunks_per_side) + ", lod levels " +
         std::to_string(s.lod_levels) + ", refine " + std::to_string(int(s.refine)) + " " +
         std::to_string(s.refine_levels) + " " + std::to_string(s.refine_max_triangles) + "\n";
}

std::string mesh_counts_bytes(const TerrainMesh& m) {
  uint64_t c[kCountFields] = {m.positions.size(), m.indices.size(), m.chunks.size(), 0};
  for (const Chunk& chunk : m.chunks) c[kLods] += chunk.lods.size();
  std::string out;
  append(out, c, kCountFields);
  return out;
}

std::string mesh_body_bytes(const TerrainMesh& m) {
  std::string out;
  append(out, m.positions.data(), m.positions.size());
  append(out, m.normals.data(), m.normals.size());
  append(out, m.uvs.data(), m.uvs.size());
  append(out, m.indices.data(), m.indices.size());
  for (const Chunk& chunk : m.chunks) {
    const ChunkRecord r{chunk.min, chunk.max, chunk.material, uint32_t(chunk.lods.size()), chunk.base_vertex};
    append(out, &r, 1);
  }
  for (const Chunk& chunk : m.chunks)
    for (const LodRange& l : chunk.lods) {
      const LodRecord r{l.first_index, l.index_count, l.error_m};
      append(out, &r, 1);
    }
  const MeshRecord r{m.min, m.max, uint64_t(m.full_triangles)};
  append(out, &r, 1);
  return out;
}

std::optional<size_t> mesh_body_size(std::span<const uint8_t> counts, size_t max_bytes) {
  uint64_t c[kCountFields];
  if (!read_counts(counts, c)) return std::nullopt;
  return body_size(c, max_bytes);
}

MeshArrays mesh_arrays(const TerrainMesh& m) {
  auto bytes = [](const auto& v) {
    return std::span(reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(v[0]));
  };
  return {bytes(m.positions), bytes(m.normals), bytes(m.uvs), bytes(m.indices)};
}

std::optional<TerrainMesh> mesh_from_bytes(std::span<const uint8_t> counts, std::span<const uint8_t> body,
                                           MeshArrays& arrays) {
  uint64_t c[kCountFields];
  if (!read_counts(counts, c)) return std::nullopt;
  const std::optional<size_t> size = body_size(c, body.size());
  if (!size || *size != body.size()) return std::nullopt;
  TerrainMesh m;
  size_t at = 0;
  auto skip = [&](size_t bytes) {
    const std::span<const uint8_t> s = body.subspan(at, bytes);
    at += bytes;
    return s;
  };
  arrays.positions = skip(c[kVertices] * sizeof(glm::vec3));
  arrays.normals = skip(c[kVertices] * sizeof(uint32_t));
  arrays.uvs = skip(c[kVertices] * sizeof(glm::vec2));
  arrays.indices = skip(c[kIndices] * sizeof(uint16_t));
  const std::vector<ChunkRecord> chunks = take<ChunkRecord>(body, at, c[kChunks]);
  const std::vector<LodRecord> lods = take<LodRecord>(body, at, c[kLods]);
  const MeshRecord mesh = take<MeshRecord>(body, at, 1)[0];
  // The vertices a level uses (its largest index plus one), all inside the mesh's; nullopt if not.
  auto used_vertices = [&](const LodRecord& l, uint32_t base_vertex) -> std::optional<uint32_t> {
    uint16_t largest = 0;
    for (size_t k = l.first_index; k < size_t(l.first_index) + l.index_count; ++k) {
      uint16_t i;
      std::memcpy(&i, arrays.indices.data() + k * sizeof(uint16_t), sizeof(i));
      largest = std::max(largest, i);
    }
    if (l.index_count == 0) return 0u;
    if (uint64_t(base_vertex) + largest >= c[kVertices]) return std::nullopt;
    return uint32_t(largest) + 1;
  };
  size_t next_lod = 0;
  for (const ChunkRecord& r : chunks) {
    if (r.lods == 0 || r.lods > lods.size() - next_lod) return std::nullopt;  // level 0 is the full mesh
    Chunk chunk{.min = r.min, .max = r.max, .material = r.material, .base_vertex = r.base_vertex};
    for (uint32_t k = 0; k < r.lods; ++k) {
      const LodRecord& l = lods[next_lod++];
      if (uint64_t(l.first_index) + l.index_count > c[kIndices] || l.index_count % 3 != 0)
        return std::nullopt;
      const std::optional<uint32_t> used = used_vertices(l, r.base_vertex);
      if (!used) return std::nullopt;
      chunk.lods.push_back(LodRange{.first_index = l.first_index,
                                    .index_count = l.index_count,
                                    .error_m = l.error_m,
                                    .vertex_count = *used});
    }
    m.chunks.push_back(std::move(chunk));
  }
  if (next_lod != lods.size()) return std::nullopt;
  m.min = mesh.min, m.max = mesh.max;
  m.full_triangles = size_t(mesh.full_triangles);
  return m;
}

}  // namespace welkin::terrain
