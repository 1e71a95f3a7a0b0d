// Chunking and levels of detail of terrain meshes (CPU only).
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
