// METAR reports through the `welkin` program as a user runs them: `render --metar` changes the sky
// the scene renders (clear is blue, overcast grey), and a bad report, on the command line, in a
// file or in a scene, is one error naming where it came from and the group, with exit code 3.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_run.h"
#include "welkin/gfx/image.h"

namespace {

namespace fs = std::filesystem;
using welkin::testing::run_welkin;
using welkin::testing::scratch_path;

// Mean blue minus red of the image's upper half (the sky): large for a clear sky, near 0 for grey.
double sky_blueness(const fs::path& png) {
  welkin::ImageU8 img = welkin::read_png(png.string());
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < img.height / 2; ++y)
    for (int x = 0; x < img.width; ++x, ++n) {
      const uint8_t* p = img.pixel(x, y);
      sum += double(p[2]) - double(p[0]);
    }
  return sum / n;
}

TEST(WeatherCli, RenderMetarSetsTheSky) {
  const fs::path clear = scratch_path("weather-cli", "clear.png"),
                 overcast = scratch_path("weather-cli", "ovc.png");
  auto r = run_welkin("render assets/scenes/weather-metar.json --size 48x27 --json --out " + clear.string() +
                      " --metar 'KLAX 271953Z 25008KT 10SM SKC 21/09 A3002'");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"weather\""), std::string::npos) << r.out;
  r = run_welkin("render assets/scenes/weather-metar.json --size 48x27 --out " + overcast.string() +
                 " --metar 'KPDX 271953Z 16006KT 4SM BR OVC012 09/08 A2992'");
  ASSERT_EQ(r.code, 0) << r.out;
  double blue_clear = sky_blueness(clear), blue_overcast = sky_blueness(overcast);
  EXPECT_GT(blue_clear, 60.0);
  EXPECT_LT(blue_overcast, 15.0);
}

TEST(WeatherCli, BadReportIsOneErrorNamingTheGroup) {
  auto r = run_welkin("render assets/scenes/weather-metar.json --size 16x9 --out " +
                      scratch_path("weather-cli", "bad.png").string() +
                      " --metar 'KSFO 271756Z 28012KT 10SM FEW0X8 18/12 A3001'");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("--metar"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("group 5 'FEW0X8' at column 27"), std::string::npos) << r.out;
  EXPECT_FALSE(r.signaled);

  const fs::path file = scratch_path("weather-cli", "report.txt");
  std::ofstream(file) << "KSFO 271756Z 28012KT 10SM FEW008 18/12 A30X1\n";
  r = run_welkin("metar --file " + file.string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find(file.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("group 7 'A30X1' at column 40"), std::string::npos) << r.out;

  const fs::path scene = scratch_path("weather-cli", "scene.json");
  std::ofstream(scene) << R"({"welkin_scene": 1, "entities": [{"components": {"weather.Report": )"
                       << R"({"metar": "KSFO 271756Z 28012KT 10SM BKN250 -RA 18/12 A3001"}}}]})";
  r = run_welkin("render " + scene.string() + " --size 16x9 --out " +
                 scratch_path("weather-cli", "s.png").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find(scene.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("weather.Report/metar"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("group 6 '-RA' at column 34"), std::string::npos) << r.out;
}

TEST(WeatherCli, MetarDecodesToJson) {
  auto r = run_welkin("metar --json 'KSFO 271756Z 28012KT 10SM FEW008 SCT025 BKN250 18/12 A3001'", false);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"genus\": \"cirrus\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"station\": \"KSFO\""), std::string::npos) << r.out;
}

}  // namespace
