#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace welkin::cli {
void print_asset_info(const std::string& file, bool json);
}

namespace welkin::assets::test {
namespace {

TEST(AssetInfo, PrintsCountsMaterialsExtensionsAndBounds) {
  GlbWriter w;
  Material mat;
  mat.name = "stone";
  MeshData mesh = grid_mesh(8);
  mesh.material = w.add_material(mat);
  w.add_node("grid", w.add_mesh(mesh, DracoSettings{.enabled = true}).mesh, {0, 5, 0});
  const fs::path f = temp_dir() / "info.glb";
  w.write(f.string());
  ::testing::internal::CaptureStdout();
  cli::print_asset_info(f.string(), false);
  const std::string text = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(text.find("81 vertices, 128 triangles"), std::string::npos) << text;
  EXPECT_NE(text.find("KHR_draco_mesh_compression"), std::string::npos);
  EXPECT_NE(text.find("stone"), std::string::npos);
  EXPECT_NE(text.find("bounds"), std::string::npos);
  ::testing::internal::CaptureStdout();
  cli::print_asset_info(f.string(), true);
  const nlohmann::json j = nlohmann::json::parse(::testing::internal::GetCapturedStdout());
  EXPECT_EQ(j["vertices"], 81);
  EXPECT_EQ(j["triangles"], 128);
  EXPECT_EQ(j["meshes"][0]["primitives"][0]["draco"], true);
  EXPECT_NEAR(j["bounds"]["min"][1].get<float>(), 4.75f, 0.01f);
  write_bytes(temp_dir() / "broken.glb", "glTF\x02");
  EXPECT_THROW(cli::print_asset_info((temp_dir() / "broken.glb").string(), false), Error);
}

}  // namespace
}  // namespace welkin::assets::test
