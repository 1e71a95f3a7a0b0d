// The committed sample terrain against the generator's report, and the generator's determinism.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace welkin::assets::test {
namespace {

using nlohmann::json;

void expect_matches_report(const Model& m, const json& report) {
  EXPECT_EQ(m.vertex_count(), report["vertices"].get<size_t>());
  EXPECT_EQ(m.triangle_count(), report["triangles"].get<size_t>());
  ASSERT_EQ(m.meshes.size(), report["meshes"].size());
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const json& r = report["meshes"][i];
    EXPECT_EQ(m.meshes[i].name, r["name"].get<std::string>());
    ASSERT_EQ(m.meshes[i].primitives.size(), 1u);
    EXPECT_EQ(m.meshes[i].primitives[0].positions.size(), r["vertices"].get<size_t>()) << r["name"];
    EXPECT_EQ(m.meshes[i].primitives[0].triangle_count(), r["triangles"].get<size_t>()) << r["name"];
    EXPECT_TRUE(m.meshes[i].primitives[0].draco);
  }
  ASSERT_EQ(m.images.size(), report["images"].size());
  for (size_t i = 0; i < m.images.size(); ++i) {
    EXPECT_EQ(m.images[i].width, report["images"][i]["width"].get<int>());
    EXPECT_EQ(m.images[i].height, report["images"][i]["height"].get<int>());
  }
  // glTF frame: X east, Y up, Z south. The ring reaches 60 km each way.
  EXPECT_NEAR(m.bounds.min.x, -60000.0f, 5.0f);
  EXPECT_NEAR(m.bounds.max.z, 60000.0f, 5.0f);
  EXPECT_GT(m.bounds.min.y, -400.0f);  // skirt bottoms
  EXPECT_LT(m.bounds.max.y, 3300.0f);  // peaks of 2-3 km
  // The runway strip (x within 1.5 km, y within 30 m) is flat at the reported elevation.
  const float z0 = report["runway_elevation_m"].get<float>();
  const Primitive& tile = m.meshes[0].primitives[0];
  size_t on_runway = 0;
  for (const glm::vec3& p : tile.positions)
    if (std::abs(p.x) <= 1500.0f && std::abs(p.z) <= 30.0f) {
      ++on_runway;
      EXPECT_NEAR(p.y, z0, 0.7f);  // 16-bit Draco positions over 40 km: 0.61 m steps
    }
  EXPECT_GT(on_runway, 40u);  // quick grids are coarser
}

TEST(Terrain, CommittedAssetHasTheReportedCounts) {
  const fs::path dir = fs::path(WELKIN_SOURCE_DIR) / "assets" / "terrain";
  if (!fs::exists(dir / "valley.glb")) GTEST_SKIP() << "assets/terrain/valley.glb not generated";
  const json report = json::parse(read_bytes(dir / "valley.json"));
  EXPECT_EQ(fs::file_size(dir / "valley.glb"), report["bytes"].get<uint64_t>());
  EXPECT_LT(fs::file_size(dir / "valley.glb"), 8u << 20);
  const Model m = load_gltf((dir / "valley.glb").string());
  expect_matches_report(m, report);
  EXPECT_NE(
      std::find(m.extensions_required.begin(), m.extensions_required.end(), "KHR_draco_mesh_compression"),
      m.extensions_required.end());
}

#ifdef WELKIN_TERRAIN_GEN
int generate(const fs::path& out, int seed) {
  const std::string cmd = std::string(WELKIN_TERRAIN_GEN) + " --quick --seed " + std::to_string(seed) +
                          " --out " + out.string() + " --report " + out.string() + ".json > /dev/null 2>&1";
  return std::system(cmd.c_str());
}

TEST(Terrain, GeneratorIsDeterministicAndReportsWhatItWrote) {
  const fs::path dir = temp_dir("terrain");
  ASSERT_EQ(generate(dir / "a.glb", 3), 0);
  ASSERT_EQ(generate(dir / "b.glb", 3), 0);
  ASSERT_EQ(generate(dir / "c.glb", 4), 0);
  const std::string a = read_bytes(dir / "a.glb");
  EXPECT_EQ(a, read_bytes(dir / "b.glb")) << "same seed, different bytes";
  EXPECT_NE(a, read_bytes(dir / "c.glb")) << "the seed changes nothing";
  const json report = json::parse(read_bytes(dir / "a.glb.json"));
  EXPECT_EQ(a.size(), report["bytes"].get<size_t>());
  expect_matches_report(load_gltf((dir / "a.glb").string()), report);
}
#endif

}  // namespace
}  // namespace welkin::assets::test
