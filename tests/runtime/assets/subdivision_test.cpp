#include "welkin/assets/subdivision.h"

#include <gtest/gtest.h>

#include <map>

#include "welkin/core/error.h"

namespace welkin::assets {
namespace {

// Regular tetrahedron, outward counter-clockwise faces; vertices at distance sqrt(3).
ControlMesh tetrahedron() {
  ControlMesh m;
  m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.face_sizes = {3, 3, 3, 3};
  m.face_indices = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
  return m;
}

// Cube [-1, 1]^3, outward counter-clockwise quads.
ControlMesh cube() {
  ControlMesh m;
  m.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  m.face_sizes = {4, 4, 4, 4, 4, 4};
  m.face_indices = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3};
  return m;
}

// A flat n x n quad grid (terrain-like open mesh) of side `size` in the XY plane.
ControlMesh grid(int n, float size) {
  ControlMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.emplace_back(size * i / n, size * j / n, 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.face_sizes.push_back(4);
      m.face_indices.insert(m.face_indices.end(), {a, a + 1, a + n + 2, a + n + 1});
    }
  return m;
}

// Every undirected edge of a closed surface is used by exactly two triangles, once in each direction.
void expect_watertight(const RefinedMesh& r) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < r.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++directed[{r.indices[t + k], r.indices[t + (k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    ASSERT_EQ(n, 1) << "edge " << e.first << "-" << e.second << " used twice in one direction";
    ASSERT_EQ(directed.count({e.second, e.first}), 1u) << "open edge " << e.first << "-" << e.second;
  }
}

TEST(Subdivision, LoopTetrahedronCountsPerLevel) {
  // Closed triangle mesh: F(l) = 4 * 4^l, E = 3F/2, V = 2 + E - F = 2 + F/2 (Euler).
  const auto counts = uniform_level_counts(tetrahedron(), SubdivScheme::loop, 4);
  const int v[] = {4, 10, 34, 130, 514}, f[] = {4, 16, 64, 256, 1024};
  ASSERT_EQ(counts.size(), 5u);
  for (int l = 0; l <= 4; ++l) {
    EXPECT_EQ(counts[size_t(l)].vertices, v[l]) << "level " << l;
    EXPECT_EQ(counts[size_t(l)].faces, f[l]) << "level " << l;
  }
}

TEST(Subdivision, CatmullClarkCubeCountsPerLevel) {
  // Closed quad mesh: F(l) = 6 * 4^l, E = 2F, V = 2 + F.
  const auto counts = uniform_level_counts(cube(), SubdivScheme::automatic, 4);
  const int v[] = {8, 26, 98, 386, 1538}, f[] = {6, 24, 96, 384, 1536};
  for (int l = 0; l <= 4; ++l) {
    EXPECT_EQ(counts[size_t(l)].vertices, v[l]) << "level " << l;
    EXPECT_EQ(counts[size_t(l)].faces, f[l]) << "level " << l;
  }
  const RefinedMesh r = refine(cube(), RefineSettings{.levels = 3});
  EXPECT_EQ(r.scheme, SubdivScheme::catmull_clark);
  EXPECT_EQ(r.positions.size(), 386u);
  EXPECT_EQ(r.triangle_count(), 2u * 384u);
  expect_watertight(r);
}

TEST(Subdivision, CatmullClarkCubeLimitSurface) {
  const RefinedMesh r = refine(cube(), RefineSettings{.levels = 4, .limit_surface = true});
  // Corner limit point: (n^2 v + 4 sum(edge nbrs) + sum(diagonals)) / (n (n + 5)) with n = 3 gives
  // (9 + 4 - 1) / 24 = 1/2 per coordinate, the farthest points (sqrt(3)/2). Face centres become regular
  // vertices after one step whose limit (16 v + 4 sum(e) + sum(d)) / 36 lies at 68/81, the nearest.
  float rmin = 1e9f, rmax = 0.0f;
  bool corner_found = false, face_centre_found = false;
  for (const glm::vec3& p : r.positions) {
    rmin = std::min(rmin, glm::length(p));
    rmax = std::max(rmax, glm::length(p));
    corner_found = corner_found || glm::length(p - glm::vec3(0.5f)) < 1e-5f;
    face_centre_found = face_centre_found || glm::length(p - glm::vec3(0.0f, 0.0f, 68.0f / 81.0f)) < 1e-5f;
    EXPECT_LE(std::abs(p.x), 1.0f);  // convex hull property
  }
  EXPECT_TRUE(corner_found);
  EXPECT_TRUE(face_centre_found);
  EXPECT_NEAR(rmin, 68.0f / 81.0f, 1e-5f);
  EXPECT_NEAR(rmax, std::sqrt(3.0f) / 2.0f, 1e-5f);
  for (size_t i = 0; i < r.positions.size(); ++i)  // outward normals
    EXPECT_GT(glm::dot(r.normals[i], glm::normalize(r.positions[i])), 0.7f) << i;
}

TEST(Subdivision, LoopTetrahedronLimitSurface) {
  const RefinedMesh r = refine(tetrahedron(), RefineSettings{.levels = 4});
  EXPECT_EQ(r.scheme, SubdivScheme::loop);
  EXPECT_EQ(r.positions.size(), 514u);
  EXPECT_EQ(r.triangle_count(), 1024u);
  // Valence-3 limit: v (1 - 3 chi) + chi sum(nbrs), chi = 1 / (3 + 3 / (8 beta)), beta = 3/16 -> chi = 1/5:
  // 0.4 (1,1,1) + 0.2 (-1,-1,-1) = (0.2, 0.2, 0.2).
  bool found = false;
  float rmax = 0.0f;
  for (const glm::vec3& p : r.positions) {
    found = found || glm::length(p - glm::vec3(0.2f)) < 1e-5f;
    rmax = std::max(rmax, glm::length(p));
  }
  EXPECT_TRUE(found);
  EXPECT_LT(rmax, std::sqrt(3.0f) * 0.2f + 1e-4f);  // the vertices are the farthest limit points
  expect_watertight(r);
}

TEST(Subdivision, TriangleBudgetLowersTheLevel) {
  const RefinedMesh r = refine(cube(), RefineSettings{.levels = 6, .max_triangles = 1000});
  EXPECT_EQ(r.level, 3);  // 768 triangles; level 4 would be 3072
  EXPECT_LE(r.triangle_count(), 1000u);
  EXPECT_THROW(refine(cube(), RefineSettings{.levels = 2, .max_triangles = 5}), Error);
}

TEST(Subdivision, AdaptiveIsDenserNearTheCameraAndCrackFree) {
  const ControlMesh g = grid(16, 1600.0f);
  RefineSettings s{
      .levels = 4, .max_triangles = 1u << 20, .camera_position = {0, 0, 10}, .adaptive_distance = 100.0f};
  const RefinedMesh r = refine(g, s);
  EXPECT_TRUE(r.adaptive);
  EXPECT_EQ(r.level, 4);
  // Vertex density near the camera corner vs the far corner.
  size_t near = 0, far = 0;
  for (const glm::vec3& p : r.positions) {
    if (p.x < 200 && p.y < 200) ++near;
    if (p.x > 1400 && p.y > 1400) ++far;
  }
  EXPECT_GT(near, 8 * far);
  // Open grid: interior edges have two triangles, boundary edges one; no T-junction cracks means
  // every directed edge's reverse exists unless it lies on the boundary of the square.
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < r.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++directed[{r.indices[t + k], r.indices[t + (k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    ASSERT_EQ(n, 1);
    if (directed.count({e.second, e.first})) continue;
    const glm::vec3 a = r.positions[e.first], b = r.positions[e.second];
    const bool on_boundary =
        (std::abs(a.x - b.x) < 1e-3f && (std::abs(a.x) < 1e-3f || std::abs(a.x - 1600) < 1e-3f)) ||
        (std::abs(a.y - b.y) < 1e-3f && (std::abs(a.y) < 1e-3f || std::abs(a.y - 1600) < 1e-3f));
    ASSERT_TRUE(on_boundary) << "crack at " << a.x << "," << a.y << " - " << b.x << "," << b.y;
  }
  for (const glm::vec3& n : r.normals) EXPECT_NEAR(n.z, 1.0f, 1e-4f);  // flat grid stays flat
  // A budget smaller than the adaptive result lowers all levels.
  s.max_triangles = r.triangle_count() / 3;
  const RefinedMesh lower = refine(g, s);
  EXPECT_LE(lower.triangle_count(), s.max_triangles);
  EXPECT_LT(lower.level, 4);
}

TEST(Subdivision, AdaptiveClosedMeshIsWatertight) {
  const RefinedMesh r =
      refine(cube(), RefineSettings{.levels = 3, .camera_position = {3, 0, 0}, .adaptive_distance = 2.5f});
  expect_watertight(r);
  for (const glm::vec3& p : r.positions) {
    EXPECT_GT(glm::length(p), 68.0f / 81.0f - 1e-5f);  // on the limit surface (see above)
    EXPECT_LT(glm::length(p), std::sqrt(3.0f) / 2.0f + 1e-5f);
  }
}

TEST(Subdivision, BadTopologyIsAnError) {
  ControlMesh m = tetrahedron();
  m.face_indices[4] = 9;
  EXPECT_THROW(refine(m, {}), Error);
  m = tetrahedron();
  m.face_indices[1] = 0;  // repeated vertex
  EXPECT_THROW(refine(m, {}), Error);
  m = cube();
  EXPECT_THROW(refine(m, RefineSettings{.scheme = SubdivScheme::loop}), Error);
  m.face_sizes.push_back(4);  // indices missing
  EXPECT_THROW(refine(m, {}), Error);
  m = cube();
  m.positions[0].x = NAN;
  EXPECT_THROW(refine(m, {}), Error);
  EXPECT_THROW(refine(cube(), RefineSettings{.levels = 11}), Error);
  try {
    ControlMesh t = tetrahedron();
    t.face_indices[4] = 9;
    refine(t, {});
  } catch (const Error& e) {
    EXPECT_EQ(e.info().path, "/face_indices/4");
  }
}

}  // namespace
}  // namespace welkin::assets
