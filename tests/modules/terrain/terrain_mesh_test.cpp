// Chunking and levels of detail of terrain meshes (CPU only).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "terrain_mesh.h"

namespace {

using namespace welkin;
using namespace welkin::terrain;

// A glTF-style (y-up) height field: n x n quads over `size` metres, gentle hills.
assets::Model grid_model(int n, float size) {
  assets::Model m;
  assets::Primitive p;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float x = size * (float(i) / n - 0.5f), z = size * (float(j) / n - 0.5f);
      p.positions.push_back({x, 40.0f * std::sin(x * 0.01f) * std::cos(z * 0.013f), z});
      p.normals.push_back({0, 1, 0});
      p.uv0.push_back({float(i) / n, float(j) / n});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      p.indices.insert(p.indices.end(), {a, c, b, b, c, d});  // counter-clockwise seen from +y
    }
  m.meshes.push_back({"grid", {p}});
  assets::Node node;
  node.mesh = 0;
  m.nodes.push_back(node);
  return m;
}

TEST(TerrainMesh, GltfYUpBecomesSceneZUp) {
  EXPECT_EQ(gltf_to_scene({1, 2, 3}), glm::vec3(1, -3, 2));  // east stays, south becomes -north, up is z
}

TEST(TerrainMesh, ChunksCoverEveryTriangleOnceAtFullDetail) {
  Terrain s;
  s.chunks_per_side = 4;
  s.lod_levels = 4;
  TerrainMesh m = build_terrain_mesh(grid_model(64, 1000.0f), s);
  EXPECT_EQ(m.full_triangles, 64u * 64u * 2u);
  EXPECT_EQ(m.chunks.size(), 16u);
  size_t lod0 = 0;
  for (const Chunk& c : m.chunks) lod0 += c.lods[0].index_count / 3;
  EXPECT_EQ(lod0, m.full_triangles);
  EXPECT_NEAR(m.min.y, -500.0f, 1e-3);  // glTF z = +500 (south) is scene y = -500
  EXPECT_NEAR(m.max.x, 500.0f, 1e-3);
}

TEST(TerrainMesh, CoarserLevelsHaveFewerTrianglesAndGrowingError) {
  Terrain s;
  s.chunks_per_side = 2;
  s.lod_levels = 4;
  TerrainMesh m = build_terrain_mesh(grid_model(64, 1000.0f), s);
  for (const Chunk& c : m.chunks) {
    ASSERT_GE(c.lods.size(), 3u);
    EXPECT_EQ(c.lods[0].error_m, 0.0f);
    for (size_t l = 1; l < c.lods.size(); ++l) {
      EXPECT_LT(c.lods[l].index_count, c.lods[l - 1].index_count);
      EXPECT_GE(c.lods[l].error_m, c.lods[l - 1].error_m);
      EXPECT_LT(c.lods[l].error_m, 100.0f) << "bounded by the hills' amplitude scale";
    }
  }
}

// Each chunk draws from its own vertices with 16-bit indices: every triangle of the source is drawn
// once, from the same corners, normals and uvs (normals within their 10-bit steps).
TEST(TerrainMesh, ChunksDrawTheSourceTrianglesFromTheirOwnVertices) {
  Terrain s;
  s.chunks_per_side = 4;
  s.lod_levels = 1;
  const assets::Model model = grid_model(64, 1000.0f);
  const TerrainMesh m = build_terrain_mesh(model, s);
  const assets::Primitive& src = model.meshes[0].primitives[0];
  // The source's triangles by their corners (scene frame), each counted once.
  std::map<std::array<float, 9>, int> triangles;
  auto key = [](glm::vec3 a, glm::vec3 b, glm::vec3 c) { return std::array<float, 9>{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}; };
  for (size_t t = 0; t < src.indices.size(); t += 3)
    ++triangles[key(gltf_to_scene(src.positions[src.indices[t]]), gltf_to_scene(src.positions[src.indices[t + 1]]),
                    gltf_to_scene(src.positions[src.indices[t + 2]]))];
  size_t drawn = 0;
  for (const Chunk& c : m.chunks) {
    for (uint32_t k = c.lods[0].first_index; k < c.lods[0].first_index + c.lods[0].index_count; k += 3) {
      const size_t a = c.base_vertex + m.indices[k], b = c.base_vertex + m.indices[k + 1], d = c.base_vertex + m.indices[k + 2];
      ASSERT_LT(std::max({a, b, d}), m.positions.size());
      EXPECT_EQ(--triangles[key(m.positions[a], m.positions[b], m.positions[d])], 0);
      for (size_t v : {a, b, d}) {
        const glm::vec3 n = unpack_normal(m.normals[v]);
        EXPECT_NEAR(n.z, 1.0f, 1e-6f);  // glTF's up (0, 1, 0) is the scene's z
        // The grid's uv is its position's fraction of the side: u = x / 1000 + 0.5, v = -y / 1000 + 0.5.
        EXPECT_NEAR(m.uvs[v].x, m.positions[v].x / 1000.0f + 0.5f, 1e-5f);
        EXPECT_NEAR(m.uvs[v].y, -m.positions[v].y / 1000.0f + 0.5f, 1e-5f);
      }
      ++drawn;
    }
  }
  EXPECT_EQ(drawn, src.indices.size() / 3);
}

// Each level draws from a prefix of its chunk's vertices, and uses every vertex of it: the coarsest
// level's first, then those each finer level adds. A draw's vertex range (vertex_count) then holds
// only the level's own vertices, the coarse levels a small part of the chunk's.
TEST(TerrainMesh, EachLevelDrawsFromAPrefixOfItsChunksVertices) {
  Terrain s;
  s.chunks_per_side = 2;
  s.lod_levels = 4;
  const TerrainMesh m = build_terrain_mesh(grid_model(64, 1000.0f), s);
  for (size_t c = 0; c < m.chunks.size(); ++c) {
    const Chunk& chunk = m.chunks[c];
    const size_t chunk_vertices = (c + 1 < m.chunks.size() ? m.chunks[c + 1].base_vertex : m.positions.size()) - chunk.base_vertex;
    ASSERT_GE(chunk.lods.size(), 3u);
    EXPECT_EQ(chunk.lods[0].vertex_count, chunk_vertices);
    for (size_t l = 0; l < chunk.lods.size(); ++l) {
      const LodRange& level = chunk.lods[l];
      std::vector<bool> used(chunk_vertices, false);
      for (uint32_t k = level.first_index; k < level.first_index + level.index_count; ++k) {
        ASSERT_LT(m.indices[k], level.vertex_count) << "chunk " << c << " level " << l;
        used[m.indices[k]] = true;
      }
      EXPECT_EQ(std::count(used.begin(), used.end(), true), level.vertex_count) << "chunk " << c << " level " << l;
      if (l > 0) EXPECT_LT(level.vertex_count, chunk.lods[l - 1].vertex_count);
    }
    EXPECT_LT(chunk.lods.back().vertex_count * 8, chunk_vertices) << "the coarsest level: a small part";
  }
}

// A cell whose triangles use more vertices than 16-bit indices reach is split into chunks.
TEST(TerrainMesh, CellsWithMoreVerticesThanSixteenBitsReachAreSplit) {
  Terrain s;
  s.chunks_per_side = 1;
  s.lod_levels = 1;
  const TerrainMesh m = build_terrain_mesh(grid_model(300, 1000.0f), s);  // 90601 vertices in one cell
  ASSERT_GE(m.chunks.size(), 2u);
  size_t triangles = 0;
  for (const Chunk& c : m.chunks) {
    const uint32_t end = (&c == &m.chunks.back()) ? uint32_t(m.positions.size()) : (&c + 1)->base_vertex;
    EXPECT_LE(end - c.base_vertex, kMaxChunkVertices);
    triangles += c.lods[0].index_count / 3;
  }
  EXPECT_EQ(triangles, 300u * 300u * 2u);
}

// Packed normals: the components GL's GL_INT_2_10_10_10_REV normalization gives back, within a step.
TEST(TerrainMesh, PackedNormalsComeBackWithinTenBitSteps) {
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.8f, 0.52f)),
                            glm::normalize(glm::vec3(-0.01f, 0.999f, -0.02f))}) {
    const glm::vec3 back = unpack_normal(pack_normal(n));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], n[i], 0.5f / 511.0f + 1e-6f) << i;
  }
  EXPECT_EQ(pack_normal(glm::vec3(0, 0, 1)), 511u << 20);
  EXPECT_EQ(pack_normal(glm::vec3(-1, 0, 0)), 0x201u);  // -511 in 10 bits
}

TEST(TerrainMesh, LodSelectionCoarsensWithDistance) {
  Chunk c;
  c.lods = {{0, 300, 0.0f}, {0, 100, 0.5f}, {0, 30, 2.0f}, {0, 9, 8.0f}};
  const double ppr = 360.0 / 1.047;  // 360 px over a 60 degree field
  EXPECT_EQ(select_lod(c, 10.0, ppr, 1.5), 0);
  // Level 1 (0.5 m) projects to 1.5 px at 0.5 * ppr / 1.5 = 114.6 m.
  EXPECT_EQ(select_lod(c, 120.0, ppr, 1.5), 1);
  EXPECT_EQ(select_lod(c, 1000.0, ppr, 1.5), 2);
  EXPECT_EQ(select_lod(c, 1e6, ppr, 1.5), 3);
}

// A grid's mesh built with these chunks and levels.
TerrainMesh grid_mesh(int n, float size, int chunks_per_side, int lod_levels) {
  Terrain s;
  s.chunks_per_side = chunks_per_side;
  s.lod_levels = lod_levels;
  return build_terrain_mesh(grid_model(n, size), s);
}

// The disk cache's bytes of a mesh give back the same mesh: its arrays read in place, its chunks,
// levels and bounds exact.
TEST(TerrainMesh, CacheBytesGiveBackTheSameMesh) {
  const TerrainMesh m = grid_mesh(32, 800.0f, 3, 3);
  const std::string counts = mesh_counts_bytes(m), body = mesh_body_bytes(m);
  auto span_of = [](const std::string& b) { return std::span(reinterpret_cast<const uint8_t*>(b.data()), b.size()); };
  ASSERT_EQ(mesh_body_size(span_of(counts), 1u << 30), body.size());
  const std::vector<uint8_t> body_bytes(body.begin(), body.end());
  MeshArrays arrays;
  const std::optional<TerrainMesh> back = mesh_from_bytes(span_of(counts), body_bytes, arrays);
  ASSERT_TRUE(back);
  const MeshArrays built = mesh_arrays(m);
  auto same = [](std::span<const uint8_t> a, std::span<const uint8_t> b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size()) == 0;
  };
  EXPECT_TRUE(same(arrays.positions, built.positions));
  EXPECT_TRUE(same(arrays.normals, built.normals));
  EXPECT_TRUE(same(arrays.uvs, built.uvs));
  EXPECT_TRUE(same(arrays.indices, built.indices));
  ASSERT_EQ(back->chunks.size(), m.chunks.size());
  for (size_t c = 0; c < m.chunks.size(); ++c) {
    EXPECT_EQ(back->chunks[c].min, m.chunks[c].min);
    EXPECT_EQ(back->chunks[c].max, m.chunks[c].max);
    EXPECT_EQ(back->chunks[c].material, m.chunks[c].material);
    ASSERT_EQ(back->chunks[c].lods.size(), m.chunks[c].lods.size());
    for (size_t l = 0; l < m.chunks[c].lods.size(); ++l) {
      EXPECT_EQ(back->chunks[c].lods[l].first_index, m.chunks[c].lods[l].first_index);
      EXPECT_EQ(back->chunks[c].lods[l].index_count, m.chunks[c].lods[l].index_count);
      EXPECT_EQ(back->chunks[c].lods[l].error_m, m.chunks[c].lods[l].error_m);
      EXPECT_EQ(back->chunks[c].lods[l].vertex_count, m.chunks[c].lods[l].vertex_count);
    }
    EXPECT_EQ(back->chunks[c].base_vertex, m.chunks[c].base_vertex);
  }
  EXPECT_EQ(back->min, m.min);
  EXPECT_EQ(back->max, m.max);
  EXPECT_EQ(back->full_triangles, m.full_triangles);
  // Settings that change the mesh change the key; the file's bytes too.
  Terrain s, other;
  other.lod_levels = s.lod_levels + 1;
  EXPECT_NE(mesh_cache_key(1, s), mesh_cache_key(1, other));
  EXPECT_NE(mesh_cache_key(1, s), mesh_cache_key(2, s));
}

// Bytes that a checksum would pass but that do not describe a mesh (a crafted or foreign cache file)
// are refused before anything is drawn from them.
TEST(TerrainMesh, CacheBytesOutOfRangeAreRefused) {
  const TerrainMesh m = grid_mesh(8, 100.0f, 2, 2);
  const std::string counts = mesh_counts_bytes(m), body = mesh_body_bytes(m);
  auto bytes = [](const std::string& b) { return std::vector<uint8_t>(b.begin(), b.end()); };
  MeshArrays arrays;
  // Body layout: per vertex a position (12 bytes), a packed normal (4) and a uv (8); 16-bit indices;
  // chunk records of 36 bytes (bounds, material, level count at 28, first vertex at 32); levels.
  const size_t first_index = m.positions.size() * (sizeof(glm::vec3) + sizeof(uint32_t) + sizeof(glm::vec2));
  const size_t first_chunk = first_index + m.indices.size() * sizeof(uint16_t);
  constexpr size_t kChunkRecord = 36;
  // An index past the vertices, counted from the last chunk's first vertex.
  std::vector<uint8_t> bad = bytes(body);
  const Chunk& last = m.chunks.back();
  const uint16_t past = uint16_t(m.positions.size() - last.base_vertex);
  std::memcpy(bad.data() + first_index + last.lods[0].first_index * sizeof(uint16_t), &past, sizeof past);
  EXPECT_FALSE(mesh_from_bytes(bytes(counts), bad, arrays));
  // A chunk's first vertex moved so that its indices reach past the vertices.
  bad = bytes(body);
  const uint32_t late = uint32_t(m.positions.size() - 1);
  std::memcpy(bad.data() + first_chunk + 32, &late, sizeof late);
  EXPECT_FALSE(mesh_from_bytes(bytes(counts), bad, arrays));
  // A level reaching past the indices (the first chunk's first level made longer).
  bad = bytes(body);
  const size_t first_lod = first_chunk + m.chunks.size() * kChunkRecord;
  const uint32_t too_many = uint32_t(m.indices.size() + 3);
  std::memcpy(bad.data() + first_lod + 4, &too_many, sizeof too_many);
  EXPECT_FALSE(mesh_from_bytes(bytes(counts), bad, arrays));
  // A chunk without levels (level 0, the full mesh, is always there): its level moved to the next chunk.
  bad = bytes(body);
  uint32_t lods_first = 0, lods_second = 0;
  std::memcpy(&lods_first, bad.data() + first_chunk + 28, sizeof lods_first);
  std::memcpy(&lods_second, bad.data() + first_chunk + kChunkRecord + 28, sizeof lods_second);
  lods_second += lods_first, lods_first = 0;
  std::memcpy(bad.data() + first_chunk + 28, &lods_first, sizeof lods_first);
  std::memcpy(bad.data() + first_chunk + kChunkRecord + 28, &lods_second, sizeof lods_second);
  EXPECT_FALSE(mesh_from_bytes(bytes(counts), bad, arrays));
  // A body shorter than its counts say, and counts too large for any limit.
  bad = bytes(body);
  bad.pop_back();
  EXPECT_FALSE(mesh_from_bytes(bytes(counts), bad, arrays));
  std::vector<uint8_t> huge = bytes(counts);
  const uint64_t vertices = uint64_t(1) << 60;
  std::memcpy(huge.data(), &vertices, sizeof vertices);
  EXPECT_FALSE(mesh_body_size(huge, size_t(4) << 30));
  EXPECT_FALSE(mesh_body_size(std::vector<uint8_t>(7), size_t(4) << 30));
  // Untouched, they pass.
  EXPECT_TRUE(mesh_from_bytes(bytes(counts), bytes(body), arrays));
}

}  // namespace
