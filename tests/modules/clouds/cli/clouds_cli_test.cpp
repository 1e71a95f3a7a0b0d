// The clouds through the `welkin` program as a user runs it: a cloudy scene renders with the clouds'
// passes timed, a bad layer value is one error and exit code 3, and `accuracy clouds` writes its
// CSVs, plot and ghosting figures.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using welkin::testing::run_welkin;
using welkin::testing::scratch_path;

TEST(CloudsCli, RenderTimesTheCloudPasses) {
  const fs::path png = scratch_path("clouds-cli", "peer.png");
  auto r = run_welkin("render assets/scenes/clouds-peer.json --size 64x36 --timings --out " + png.string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* pass : {"clouds.shadow_map", "clouds.march", "clouds.composite"})
    EXPECT_NE(r.out.find(pass), std::string::npos) << pass << "\n" << r.out;
  EXPECT_TRUE(fs::exists(png));
}

TEST(CloudsCli, BadLayerValueIsOneErrorAndExitCodeThree) {
  const fs::path png = scratch_path("clouds-cli", "bad.png");
  auto r = run_welkin("render assets/scenes/clouds-peer.json --size 16x9 --set clouds.VolumetricClouds/layers/0/thickness_m=-5 --out " +
                      png.string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("layers/0/thickness_m"), std::string::npos) << r.out;
  EXPECT_FALSE(r.signaled);
}

TEST(CloudsCli, AccuracyWritesTablesPlotAndGhosting) {
  const fs::path out = scratch_path("clouds-cli", "accuracy");
  auto r = run_welkin("accuracy clouds --quick --qualities low --size 64x36 --frames 1 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* f : {"accuracy-clouds.csv", "accuracy-clouds-rays.csv", "accuracy-clouds.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  std::ifstream csv(out / "accuracy-clouds.csv");
  std::string header, diffusion, octaves;
  std::getline(csv, header), std::getline(csv, diffusion), std::getline(csv, octaves);
  EXPECT_EQ(diffusion.rfind("diffusion/low,", 0), 0u) << diffusion;
  EXPECT_EQ(octaves.rfind("octaves/low,", 0), 0u) << octaves;
  EXPECT_NE(r.out.find("clipped history"), std::string::npos) << r.out;
}

}  // namespace
