// The painted coverage map on llvmpipe: where it is painted full the layers that follow it are
// overcast, where it is painted empty they are clear, a neutral map changes nothing, and the CPU
// mirror of the field (what the reference path tracer marches) sees the same map at the same place.
#include <unistd.h>

#include <filesystem>

#include "clouds_test_support.h"
#include "validation/cloud_field.h"
#include "welkin/core/error.h"
#include "welkin/scene/painted_map.h"
#include "scratch_folder.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A 64-texel map of 40 km: the west half painted `west`, the east half `east`.
std::string write_map(const std::string& name, uint8_t west, uint8_t east) {
  const fs::path& dir = welkin::testing::scratch_folder("welkin-coverage-map-test");
  const std::string file = (dir / name).string();
  PaintedMaps maps;
  PaintedMap& m = maps.create(file, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) m.texels[size_t(y) * 64 + size_t(x)] = x < 32 ? west : east;
  maps.save(file);
  return file;
}

// One stratus sheet (1000-1600 m) at the given coverage, seen from the ground at `east_m`, looking up.
json sheet(double coverage, const std::string& map, double east_m, bool follows = true) {
  json clouds = {{"layers", json::array({{{"genus", "stratus"}, {"coverage", coverage}, {"base_altitude_m", 1000},
                                          {"thickness_m", 600}, {"base_variation_m", 0}, {"density_per_m", 0.02},
                                          {"follows_coverage_map", follows}}})},
                 {"coverage_map", map},
                 {"coverage_map_size_m", 40000.0},
                 {"temporal_upscaling", false}};
  json d = test::noon(clouds);
  for (auto& e : d["entities"])
    if (e["components"].contains("core.Camera")) e["components"]["core.Camera"]["position_m"] = {east_m, 0, 2}, e["components"]["core.Camera"]["pitch_deg"] = 60;
  return d;
}

double mean_difference(const ImageF& a, const ImageF& b) {
  double sum = 0.0, ref = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) sum += std::abs(double(a.rgba[i]) - b.rgba[i]), ref += std::abs(double(b.rgba[i]));
  return sum / std::max(ref, 1e-30);
}

TEST(CloudsCoverageMap, PaintedFullIsOvercastPaintedEmptyIsClearNeutralChangesNothing) {
  const std::string split = write_map("split.png", 0, 255), neutral = write_map("neutral.png", 128, 128);
  // A layer of coverage 0 is marched only because the map can raise it.
  test::Rendered east = test::render(sheet(0.0, split, 8000.0), 48, 27);
  EXPECT_TRUE(east.ran("clouds.march"));
  const CloudsGpu& gpu = east.world->resource<CloudsGpu>();
  ASSERT_EQ(gpu.layers.size(), 1u);
  EXPECT_EQ(gpu.layers[0].follows_map, 1.0f);
  EXPECT_FLOAT_EQ(gpu.block.map_raise, 1.0f);  // texel 255 adds a full coverage
  test::Rendered ignoring = test::render(sheet(0.0, split, 8000.0, false), 48, 27);
  EXPECT_FALSE(ignoring.ran("clouds.march"));
  const ImageF clear_sky = ignoring.renderer->read_hdr();

  // East of the origin the deck is overcast: the sky above is hidden.
  EXPECT_GT(mean_difference(east.renderer->read_hdr(), clear_sky), 0.3);
  // West of it the map clears even a layer of coverage 1 (texel 0 takes ~1.008 away).
  test::Rendered west = test::render(sheet(1.0, split, -8000.0), 48, 27);
  test::Rendered west_clear = test::render(sheet(0.0, split, -8000.0, false), 48, 27);
  EXPECT_LT(mean_difference(west.renderer->read_hdr(), west_clear.renderer->read_hdr()), 1e-3);
  // A neutral map is the same as none.
  test::Rendered with_neutral = test::render(sheet(0.5, neutral, 8000.0), 48, 27);
  test::Rendered without = test::render(sheet(0.5, "", 8000.0), 48, 27);
  EXPECT_LT(mean_difference(with_neutral.renderer->read_hdr(), without.renderer->read_hdr()), 1e-4);
}

TEST(CloudsCoverageMap, TheCpuMirrorReadsTheMapAtTheSamePlaces) {
  const std::string split = write_map("split-cpu.png", 0, 255);
  test::Rendered r = test::render(sheet(0.5, split, 3000.0), 16, 9);
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  const CloudField field(read_noise(gpu), gpu.block, gpu.layers);
  // Camera-relative points in the middle of the sheet: east of the map's centre (x > 0 in the world),
  // overcast everywhere; west of it, clear everywhere; off the map, the layer's own 50%.
  int east_cloud = 0, west_cloud = 0, off_cloud = 0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const double across = -15000.0 + 30000.0 * (i + 0.5) / n;
    const double camera_east = 3000.0;  // world x of the camera
    east_cloud += field.extinction({1000.0 + 2000.0 * (i % 4) - camera_east, across, 1300.0}) > 0.0;
    west_cloud += field.extinction({-4000.0 - 2000.0 * (i % 4) - camera_east, across, 1300.0}) > 0.0;
    off_cloud += field.extinction({25000.0 + 10.0 * i - camera_east, across, 1300.0}) > 0.0;
  }
  EXPECT_GE(east_cloud, n * 9 / 10);  // the shape noise erodes a little even of a full sheet
  EXPECT_EQ(west_cloud, 0);
  EXPECT_GT(off_cloud, n / 5);
  EXPECT_LT(off_cloud, n * 4 / 5);
}

TEST(CloudsCoverageMap, AMissingMapIsAnErrorNamingTheField) {
  try {
    test::render(sheet(0.5, "/nonexistent/welkin-map.png", 0.0), 16, 9);
    FAIL() << "rendered with a missing map";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clouds.VolumetricClouds/coverage_map"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("welkin-map.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace welkin::clouds
