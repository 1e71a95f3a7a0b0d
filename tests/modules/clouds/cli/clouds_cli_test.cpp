// The clouds through the `welkin` program as a user runs it: a cloudy scene renders with the clouds'
// passes timed, a bad layer value is one error and exit code 3, and `accuracy clouds` writes its
// CSVs, plot and ghosting figures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
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
  for (const char* f : {"accuracy-clouds.csv", "accuracy-clouds-rays.csv", "accuracy-clouds-terms.csv", "accuracy-clouds.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  std::ifstream csv(out / "accuracy-clouds.csv");
  std::string header, diffusion, octaves;
  std::getline(csv, header), std::getline(csv, diffusion), std::getline(csv, octaves);
  EXPECT_EQ(diffusion.rfind("diffusion/low,", 0), 0u) << diffusion;
  EXPECT_EQ(octaves.rfind("octaves/low,", 0), 0u) << octaves;
  EXPECT_NE(r.out.find("clipped history"), std::string::npos) << r.out;
  for (const char* motion : {"still", "turning", "flying"})  // the silhouettes after the upscaling
    EXPECT_NE(r.out.find(std::string("  ") + motion + " "), std::string::npos) << motion << "\n" << r.out;
}

// --rays: a value out of range is one error naming the file and the path inside it.
TEST(CloudsCli, BadRayIsOneErrorNamingTheFileAndPath) {
  const fs::path rays = scratch_path("clouds-cli", "bad-rays.json");
  std::ofstream(rays) << R"({"rays": [{"position_m": [0, 0, 100], "heading_deg": 0, "pitch_deg": 30},
                                     {"position_m": [0, 0, 100], "heading_deg": 0, "pitch_deg": 120}]})";
  auto r = run_welkin("accuracy clouds --rays " + rays.string() + " --qualities low --out " + scratch_path("clouds-cli", "bad-rays").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find(rays.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("/rays/1/pitch_deg"), std::string::npos) << r.out;
  EXPECT_FALSE(r.signaled);
}

// --scene and --rays measure a case nobody tuned for: one row per ray and quality in the CSV.
TEST(CloudsCli, SceneAndRaysMeasureEveryRay) {
  const fs::path out = scratch_path("clouds-cli", "scene-rays");
  const fs::path rays = scratch_path("clouds-cli", "two-rays.json");
  std::ofstream(rays) << R"({"rays": [{"position_m": [0, 0, 300], "heading_deg": 110, "pitch_deg": 55},
                                     {"position_m": [500, -300, 3000], "heading_deg": 290, "pitch_deg": -35}]})";
  auto r = run_welkin("accuracy clouds --quick --scene modules/clouds/validation/holdout/stratocumulus-low-sun.json --rays " +
                      rays.string() + " --qualities low --size 32x18 --frames 1 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream csv(out / "accuracy-clouds-rays.csv");
  std::string line;
  int rows = 0;
  for (std::getline(csv, line); std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 4);  // two rays, two models
}

// The fit's problem, ray by ray: each term's column is what that term alone adds to the march. The
// light no weight scales (here the sunlight a cirrus deck scatters down onto a haze, which lights it as
// the sky does) is in every term's march and must come out once: left in, each term's column held it
// again, scaled up 64 times by the term's marching weight, and the weights were solved for a march that
// is not the one they compile into (on the peer scene's rays the sum put the march at 2.2 times the path
// tracer's where it measured 0.56). The fit reports how far its sum and the march of its weights part:
// measured 0.05% of the mean; with the light left in, 9.2%.
TEST(CloudsCli, TheFitsSumIsTheMarchOfItsWeights) {
  const fs::path out = scratch_path("clouds-cli", "fit-unweighted");
  const fs::path scene = scratch_path("clouds-cli", "haze.json"), rays = scratch_path("clouds-cli", "haze-rays.json");
  std::ofstream(scene) << R"({"welkin_scene": 1, "entities": [
    {"name": "atmosphere", "components": {"atmosphere.Atmosphere": {}}},
    {"name": "sun", "components": {"atmosphere.Sun": {"azimuth_deg": 240, "elevation_deg": 10}}},
    {"name": "haze", "components": {"clouds.VolumetricClouds": {"layers": [
      {"genus": "stratus", "base_altitude_m": 0, "thickness_m": 300, "coverage": 1.0, "density_per_m": 0.002,
       "shape_amount": 0.0, "detail_amount": 0.0},
      {"genus": "cirrus", "base_altitude_m": 7500, "thickness_m": 500, "coverage": 1.0, "density_per_m": 0.003,
       "shape_amount": 0.0, "detail_amount": 0.0, "casts_shadow": false}]}}}]})";
  std::ofstream(rays) << R"({"rays": [{"position_m": [0, 0, 100], "heading_deg": 200, "pitch_deg": 3}]})";
  auto r = run_welkin("accuracy clouds --quick --fit --scene " + scene.string() + " --rays " + rays.string() +
                      " --qualities low --fit-terms 5,45 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string key = "the fitted sum against the march of its weights: ";
  const size_t at = r.out.find(key);
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LT(std::stod(r.out.substr(at + key.size())), 0.5) << r.out;
  // Weights that light the haze (the path tracer's is brighter than its single scattering), or the two
  // would agree whatever the columns held.
  const size_t w5 = r.out.find("W5="), w45 = r.out.find("W45=");
  ASSERT_TRUE(w5 != std::string::npos && w45 != std::string::npos) << r.out;
  EXPECT_GT(std::stod(r.out.substr(w5 + 3)) + std::stod(r.out.substr(w45 + 4)), 0.0) << r.out;
}

// The fit's options are one clear error before any ray is path traced (minutes a set of rays).
TEST(CloudsCli, ABadFitOptionIsOneErrorBeforeAnyPathIsTraced) {
  const fs::path out = scratch_path("clouds-cli", "fit-bad");
  for (const std::string& option : {std::string("--fit-terms 52"), std::string("--fit-also nocomma.json")}) {
    auto r = run_welkin("accuracy clouds --quick --fit " + option +
                        " --scene modules/clouds/validation/holdout/stratocumulus-low-sun.json --rays "
                        "modules/clouds/validation/holdout/stratocumulus-rays.json --qualities low --out " +
                        out.string());
    EXPECT_EQ(r.code, 3) << r.out;
    EXPECT_NE(r.out.find(option.substr(0, option.find(' '))), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("reference 1/"), std::string::npos) << r.out;
    EXPECT_FALSE(r.signaled);
  }
}

// --image: the march beside the path tracer's image of the same rays, with the image-wide error.
TEST(CloudsCli, ImageWritesThePanelsAndTheError) {
  const fs::path out = scratch_path("clouds-cli", "image");
  auto r = run_welkin("accuracy clouds --image modules/clouds/validation/holdout/stratocumulus-low-sun.json --size 12x8 "
                      "--paths-per-pixel 8 --qualities low --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / "clouds-image-stratocumulus-low-sun-low.png"));
  EXPECT_NE(r.out.find("relative RMSE"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(" over 0 cloud pixels"), std::string::npos) << r.out;  // the deck covers part of the view
  // Each panel's radiances pixel by pixel: a row a pixel, the rows from the top, every value finite.
  std::ifstream csv(out / "clouds-image-stratocumulus-low-sun-low.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "x,y,march,reference,reference_ci95,reference_transmittance");
  int rows = 0, clouds = 0;
  for (; std::getline(csv, line); ++rows) {
    double v[6];
    const int read =
        std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]);
    ASSERT_EQ(read, 6) << line;
    EXPECT_EQ(int(v[0]) + 12 * int(v[1]), rows) << line;
    for (double x : v) EXPECT_TRUE(std::isfinite(x) && x >= 0.0) << line;
    clouds += v[5] < 0.999 ? 1 : 0;
  }
  EXPECT_EQ(rows, 12 * 8);
  EXPECT_GT(clouds, 0);  // the deck covers part of the view in the path tracer's panel too
}

// --image with --paths-per-pixel 0: no path tracing; the shipped frame beside the march at every pixel,
// the ratio of their means, their isolated pixels and every pixel's values in a CSV.
TEST(CloudsCli, ImageWithoutPathsComparesTheShippedFrameWithTheFullMarch) {
  const fs::path out = scratch_path("clouds-cli", "image-no-paths");
  auto r = run_welkin("accuracy clouds --image modules/clouds/validation/holdout/stratocumulus-low-sun.json --size 12x8 "
                      "--paths-per-pixel 0 --qualities low --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / "clouds-image-stratocumulus-low-sun-low-against-every-pixel.png"));
  EXPECT_NE(r.out.find("mean of the shipped frame"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("relative RMSE"), std::string::npos) << r.out;  // nothing path traced
  std::ifstream csv(out / "clouds-image-stratocumulus-low-sun-low-marches.csv");
  std::string line;
  int rows = 0;
  for (std::getline(csv, line); std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 12 * 8);
}

// The figures `welkin accuracy clusters|billboards --json` prints at the switch distance (the
// cheaper path against the raymarch of the same layer alone), from its output.
nlohmann::json switch_figures(const std::string& path, const std::string& size,
                              const std::string& scene = "") {
  const fs::path out = scratch_path(
      "clouds-cli", "switch-" + path + (scene.empty() ? "" : "-" + fs::path(scene).stem().string()));
  auto r = run_welkin("accuracy " + path + (scene.empty() ? "" : " --scene " + scene) +
                          " --quick --json --frames 1 --size " + size + " --out " + out.string(),
                      false);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / ("switch-" + path + ".png")));
  const size_t begin = r.out.find("\n{"), end = r.out.rfind("\n}");
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    ADD_FAILURE() << "no JSON in\n" << r.out;
    return {};
  }
  return nlohmann::json::parse(r.out.substr(begin + 1, end - begin + 1));
}

// The hand-over (issue 35, docs/clouds-far.md): each path against the raymarch over the pixels whose
// ray meets the layer's base around the switch. Measured at 160x90 on main's refitted light model:
// the clusters (columns marched through the field in one step, lit by the shadow map, magnified
// through a B-spline) -12.6% in mean and 32.1% per pixel (before the B-spline -14.9% and 35.0%; the
// smooth ellipsoids -15.2% and 38.2%); the billboards +13.2% and 27.0% (+8.5% and 26.5% under the
// light model before the refit). The bounds leave about two points. On the billowed field (docs/clouds.md,
// "Shape") the billboards measure +20.3% and 25.2% (their cover 79% against the march's 90%); with
// the light model's terms 30-31 (the fill of the un-eroded envelope, which the billboards' atlas does
// not carry: they read 1, the march less between billows) +30.0% and 31.2%; with the fill baked into
// the atlas +15.1% and 19.4%; with the archetypes windowed from 0.8 of their half width (was 0.55) and
// thinned only below the weakest archetype +8.7% and 15.6%. The clusters on the billowed field with
// terms 30-31: -1.7% and 30.6% (-0.6% and 31.1% on 2026-11-28); each step's sample placed by the
// layer's envelope at four points (docs/clouds-far.md, "The envelope's candidates"): +2.5% and 20.9%.
// The billboards lit through the shadow map too (the average of their archetype's optical depth and
// the field's; docs/clouds-far.md, "The billboards' light from the shadow map"): +3.9% and 15.0%.
// The bounds leave about two points. The issue's aim, 2% and 12%, is not met yet.
TEST(CloudsCli, CheaperPathsAgreeWithTheMarchAtTheSwitch) {
  const nlohmann::json clusters = switch_figures("clusters", "160x90");
  ASSERT_TRUE(clusters.contains("pixel_luminance_difference")) << clusters.dump();
  EXPECT_GT(clusters["band_pixels"].get<int>(), 500);
  EXPECT_LE(std::abs(clusters["mean_luminance_difference"].get<double>()), 0.04) << clusters.dump();
  EXPECT_LE(clusters["pixel_luminance_difference"].get<double>(), 0.23) << clusters.dump();
  const nlohmann::json billboards = switch_figures("billboards", "160x90");
  ASSERT_TRUE(billboards.contains("pixel_luminance_difference")) << billboards.dump();
  EXPECT_GT(billboards["band_pixels"].get<int>(), 100);
  EXPECT_LE(std::abs(billboards["mean_luminance_difference"].get<double>()), 0.06) << billboards.dump();
  EXPECT_LE(billboards["pixel_luminance_difference"].get<double>(), 0.17) << billboards.dump();
}

// The billboards under a sun 25 degrees up behind the camera, where the shade of the field's other
// clouds counts most: lit by their archetype alone they were 28.2% brighter than the march at 160x90
// (per pixel 30.7%); through the shadow map as well (billboard.frag) -11.6% and 17.8%. The bounds leave
// about two points.
TEST(CloudsCli, BillboardsUnderALowSunAreShadedByTheFieldsOtherClouds) {
  nlohmann::json doc = nlohmann::json::parse(std::ifstream("assets/scenes/clouds-billboards.json"));
  for (auto& e : doc["entities"])
    if (e["components"].contains("atmosphere.Sun"))
      e["components"]["atmosphere.Sun"] = {{"azimuth_deg", 330}, {"elevation_deg", 25}};
  const fs::path scene = scratch_path("clouds-cli", "billboards-low-sun.json");
  std::ofstream(scene) << doc.dump();
  const nlohmann::json figures = switch_figures("billboards", "160x90", scene.string());
  ASSERT_TRUE(figures.contains("pixel_luminance_difference")) << figures.dump();
  EXPECT_GT(figures["band_pixels"].get<int>(), 100);
  EXPECT_LE(std::abs(figures["mean_luminance_difference"].get<double>()), 0.14) << figures.dump();
  EXPECT_LE(figures["pixel_luminance_difference"].get<double>(), 0.20) << figures.dump();
}

}  // namespace
