#include "terrain_mesh.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>

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
      const uint32_t base = uint32_t(out.positions.size());
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (const auto& p : f.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
      out.min = glm::min(out.min, lo);
      out.max = glm::max(out.max, hi);
      out.positions.insert(out.positions.end(), f.positions.begin(), f.positions.end());
      out.normals.insert(out.normals.end(), f.normals.begin(), f.normals.end());
      out.uvs.insert(out.uvs.end(), f.uvs.begin(), f.uvs.end());
      out.full_triangles += f.indices.size() / 3;
      // Bucket triangles by centroid on an n x n grid over the primitive's ground footprint.
      std::vector<std::vector<uint32_t>> buckets(size_t(n) * n);
      glm::vec2 extent = glm::max(glm::vec2(hi - lo), glm::vec2(1e-3f));
      for (size_t t = 0; t + 2 < f.indices.size(); t += 3) {
        glm::vec3 c = (f.positions[f.indices[t]] + f.positions[f.indices[t + 1]] + f.positions[f.indices[t + 2]]) / 3.0f;
        int cx = std::clamp(int((c.x - lo.x) / extent.x * n), 0, n - 1);
        int cy = std::clamp(int((c.y - lo.y) / extent.y * n), 0, n - 1);
        auto& b = buckets[size_t(cy) * n + cx];
        b.insert(b.end(), {f.indices[t], f.indices[t + 1], f.indices[t + 2]});
      }
      // Each chunk is simplified on its own compact vertex set (cost proportional to the chunk).
      std::vector<int32_t> to_local(f.positions.size(), -1);
      for (auto& b : buckets) {
        if (b.empty()) continue;
        std::vector<uint32_t> global;
        std::vector<glm::vec3> local_pos;
        std::vector<uint32_t> local_idx;
        for (uint32_t i : b) {
          if (to_local[i] < 0) {
            to_local[i] = int32_t(global.size());
            global.push_back(i);
            local_pos.push_back(f.positions[i]);
          }
          local_idx.push_back(uint32_t(to_local[i]));
        }
        for (uint32_t g : global) to_local[g] = -1;
        // meshopt reports error relative to the extent of the vertices it was given.
        const float scale = meshopt_simplifyScale(&local_pos[0].x, local_pos.size(), sizeof(glm::vec3));
        Chunk chunk;
        chunk.material = f.material;
        chunk.min = glm::vec3(INFINITY);
        chunk.max = glm::vec3(-INFINITY);
        for (uint32_t i : b) chunk.min = glm::min(chunk.min, f.positions[i]), chunk.max = glm::max(chunk.max, f.positions[i]);
        std::vector<uint32_t> level = local_idx;
        for (int l = 0; l < std::max(1, s.lod_levels); ++l) {
          float error = 0.0f;
          if (l > 0) {
            std::vector<uint32_t> coarser(level.size());
            size_t target = std::max<size_t>(3, level.size() / 4 / 3 * 3);
            // Borders locked: the chunk's outline stays identical at every level, so no cracks.
            coarser.resize(meshopt_simplify(coarser.data(), level.data(), level.size(), &local_pos[0].x, local_pos.size(),
                                            sizeof(glm::vec3), target, 1.0f, meshopt_SimplifyLockBorder, &error));
            if (coarser.size() >= level.size()) break;  // nothing left to remove
            level = std::move(coarser);
          }
          LodRange r{uint32_t(out.indices.size()), uint32_t(level.size()),
                     std::max(error * scale, chunk.lods.empty() ? 0.0f : chunk.lods.back().error_m)};
          for (uint32_t i : level) out.indices.push_back(base + global[i]);
          chunk.lods.push_back(r);
        }
        out.chunks.push_back(std::move(chunk));
      }
    }
  }
  if (out.positions.empty()) throw Error(ErrorInfo{.file = model.file, .message = "the model has no triangles to draw"});
  return out;
}

int select_lod(const Chunk& chunk, double distance_m, double pixels_per_radian, double pixel_error) {
  int chosen = 0;
  for (int l = 1; l < int(chunk.lods.size()); ++l)
    if (chunk.lods[size_t(l)].error_m / std::max(distance_m, 1e-3) * pixels_per_radian <= pixel_error) chosen = l;
  return chosen;
}

}  // namespace welkin::terrain
