// The atmosphere through the `welkin` program as a user runs it: bad parameters are one clear line
// and exit code 3 (never a black image), `probe` prints any method's numbers, and `accuracy` writes
// its report (a tiny smoke run; the real sweep is not part of ctest).
#include <gtest/gtest.h>

#include "cli_run.h"
#include "welkin/gfx/image.h"
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

using welkin::testing::CliRun;

CliRun run(const std::string& args, bool with_stderr = true) { return welkin::testing::run_welkin(args, with_stderr); }

fs::path tmp(const std::string& name) { return welkin::testing::scratch_path("welkin-atmosphere-cli", name); }

fs::path scene_with_atmosphere(const std::string& name, const std::string& atmosphere_fields) {
  fs::path p = tmp(name);
  std::ofstream(p) << R"({"welkin_scene": 1, "entities": [)"
                   << R"({"name": "camera", "components": {"core.Camera": {"pitch_deg": 10}}},)"
                   << R"({"name": "air", "components": {"atmosphere.Atmosphere": {)" << atmosphere_fields
                   << "}}}]}";
  return p;
}

void expect_one_line_error(const CliRun& r, const std::string& file, const std::string& path) {
  EXPECT_FALSE(r.signaled) << "no crash";
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find(file), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(path), std::string::npos) << r.out;
}

TEST(AtmosphereCli, BadParametersAreOneClearLineNotABlackImage) {
  const std::string at = "at /entities/1/components/atmosphere.Atmosphere/";
  struct Case {
    std::string name, fields, path;
  } cases[] = {
      {"negative.json", R"("rayleigh_scattering": [0.0058, -0.0135, 0.0331])", at + "rayleigh_scattering/1"},
      {"top_below_bottom.json", R"("bottom_radius_km": 6360, "top_radius_km": 6300)", at + "top_radius_km"},
      {"absorbing_mie.json",
       R"("mie_scattering": [0.004, 0.004, 0.004], "mie_extinction": [0.003, 0.004, 0.004])",
       at + "mie_extinction/0"},
      {"anisotropy.json", R"("mie_g": 1.5)", at + "mie_g"},
      {"empty_shell.json", R"("bottom_radius_km": 6360, "top_radius_km": 6360)", at + "top_radius_km"},
  };
  for (const Case& c : cases) {
    const fs::path scene = scene_with_atmosphere(c.name, c.fields);
    const fs::path out = tmp(c.name + ".png");
    CliRun r = run("render " + scene.string() + " --size 16x9 --out " + out.string());
    expect_one_line_error(r, scene.string() + ": " + c.path, c.path);
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // A number too large for a double is the JSON reader's error, still one line naming the file.
  const fs::path overflow = scene_with_atmosphere("overflow.json", R"("mie_g": 1e999)");
  expect_one_line_error(run("render " + overflow.string() + " --size 16x9 --out " + tmp("o.png").string()),
                        overflow.string(), "1e999");
  // NaN cannot be written in JSON; --set reaches the same checks with the field's full path.
  const fs::path good = scene_with_atmosphere("good.json", "");
  CliRun r = run("render " + good.string() + " --size 16x9 --set atmosphere.Atmosphere/mie_g=nan --out " +
                 tmp("nan.png").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find("atmosphere.Atmosphere/mie_g"), std::string::npos) << r.out;
}

TEST(AtmosphereCli, ProbePrintsEveryMethodAsJson) {
  const std::string ray =
      "--altitude-km 1 --view-zenith-deg 80 --view-azimuth-deg 30 --sun-zenith-deg 60 "
      "--sun-azimuth-deg 0 --size 16x9 --json";
  for (const char* method : {"reference", "lut", "raymarch"}) {
    CliRun r = run(std::string("probe --method ") + method + " --orders 1 " + ray, false);
    ASSERT_EQ(r.code, 0) << method << ": " << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["method"], method);
    ASSERT_EQ(j["transmittance"].size(), 3u);
    ASSERT_EQ(j["radiance"].size(), 3u);
    EXPECT_TRUE(j["ms"].is_number());
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(j["radiance"][c].get<double>(), 0.0) << method;
      EXPECT_GT(j["transmittance"][c].get<double>(), 0.0) << method;
      EXPECT_LT(j["transmittance"][c].get<double>(), 1.0) << method;
    }
  }
  CliRun pt = run("probe --method pathtrace --orders all --samples 2048 " + ray, false);
  ASSERT_EQ(pt.code, 0) << pt.out;
  EXPECT_EQ(nlohmann::json::parse(pt.out)["samples"], 2048);
}

TEST(AtmosphereCli, ProbeSetTakesShortAndFullFieldPathsThroughTheRuntime) {
  const std::string args = "probe --method reference --json --view-zenith-deg 70 ";
  CliRun base = run(args, false), shorthand = run(args + "--set atmosphere.mie_g=0.76", false),
         full = run(args + "--set atmosphere.Atmosphere/mie_g=0.76", false);
  ASSERT_EQ(shorthand.code, 0) << shorthand.out;
  ASSERT_EQ(full.code, 0) << full.out;
  const auto radiance = [](const CliRun& r) { return nlohmann::json::parse(r.out)["radiance"]; };
  EXPECT_EQ(radiance(shorthand), radiance(full));
  EXPECT_NE(radiance(shorthand), radiance(base));
  // Out of range and unknown fields: the runtime's one-line errors, naming the field.
  CliRun bad = run(args + "--set atmosphere.mie_g=2");
  EXPECT_EQ(bad.code, 3) << bad.out;
  EXPECT_NE(bad.out.find("atmosphere.Atmosphere/mie_g"), std::string::npos) << bad.out;
  CliRun unknown = run(args + "--set atmosphere.mie_gg=0.5");
  EXPECT_EQ(unknown.code, 3) << unknown.out;
  EXPECT_NE(unknown.out.find("mie_gg"), std::string::npos) << unknown.out;
  CliRun single_only = run("probe --method reference --orders all");
  EXPECT_EQ(single_only.code, 3) << single_only.out;
  EXPECT_NE(single_only.out.find("--orders"), std::string::npos) << single_only.out;
}

TEST(AtmosphereCli, AccuracyWritesItsReport) {
  const fs::path out = tmp("accuracy");
  CliRun r = run("accuracy atmosphere --quick --methods lut --qualities low --size 32x18 --frames 1 --out " +
                 out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* f : {"accuracy-atmosphere.csv", "accuracy-atmosphere-rays.csv", "accuracy-atmosphere.png"})
    EXPECT_GT(fs::file_size(out / f), 100u) << f;
  std::ifstream csv(out / "accuracy-atmosphere.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(row.rfind("lut,low,", 0), 0u) << row;
  EXPECT_NE(r.out.find("| lut | low |"), std::string::npos) << r.out;
}

// `--check` holds the run to the committed tolerance table: the table passes at CI's quick size (every
// method and quality), a limit tighter than what is measured fails with its name, and a malformed table
// is one error naming the file and the path inside it before anything is measured.
TEST(AtmosphereCli, AccuracyCheckHoldsTheCommittedTolerances) {
  const std::string quick = "accuracy atmosphere --quick --size 16x9 --frames 1 --check --out ";
  CliRun ok = run(quick + tmp("check-ok").string());
  ASSERT_EQ(ok.code, 0) << ok.out;
  EXPECT_NE(ok.out.find("0 of 72 limits exceeded (quick rays)"), std::string::npos) << ok.out;

  const fs::path tight = tmp("tight.json");
  std::ofstream(tight) << R"({"welkin_accuracy_tolerances": 1, "limits": [)"
                       << R"({"method": "lut", "quality": "high", "orders": "all", "band": "sun>=3", "rays": "quick", "rmse": 0.001, "max": 1.0}]})";
  CliRun fail = run("accuracy atmosphere --quick --methods lut --qualities high --size 16x9 --frames 1 --check --tolerances " +
                    tight.string() + " --out " + tmp("check-tight").string());
  EXPECT_EQ(fail.code, 1) << fail.out;
  EXPECT_NE(fail.out.find("lut high, orders all, sun>=3"), std::string::npos) << fail.out;
  EXPECT_NE(fail.out.find("1 of 1 limits exceeded"), std::string::npos) << fail.out;

  const fs::path bad = tmp("bad.json");
  std::ofstream(bad) << R"({"welkin_accuracy_tolerances": 1, "limits": [{"method": "lut", "quality": "best"}]})";
  expect_one_line_error(run("accuracy atmosphere --quick --check --tolerances " + bad.string() + " --out " + tmp("check-bad").string()),
                        bad.string(), "/limits/0/quality");
}

// `--write-tolerances` turns a run's errors into the limits of its ray set (the measured value plus
// 15% and 0.1 point, rounded up), keeps the other set's limits, and the table it writes passes.
TEST(AtmosphereCli, AccuracyWritesTheTolerancesItMeasured) {
  const fs::path given = tmp("given.json"), written = tmp("written.json"), out = tmp("write-out");
  std::ofstream(given) << R"({"welkin_accuracy_tolerances": 1, "limits": [)"
                       << R"({"method": "raymarch", "quality": "ultra", "orders": "all", "band": "sun=0", "rays": "all", "rmse": 0.5, "max": 0.5},)"
                       << R"({"method": "lut", "quality": "low", "orders": "all", "band": "sun>=3", "rays": "quick", "rmse": 0.001, "max": 0.001}]})";
  const std::string run_low = "accuracy atmosphere --quick --methods lut --qualities low --size 16x9 --frames 1 ";
  CliRun w = run(run_low + "--tolerances " + given.string() + " --write-tolerances " + written.string() + " --out " +
                 out.string());
  ASSERT_EQ(w.code, 0) << w.out;
  const nlohmann::json table = nlohmann::json::parse(std::ifstream(written));
  int kept = 0, quick = 0;
  double rmse_limit = -1.0;
  for (const auto& l : table["limits"]) {
    if (l["rays"] == "all") {
      ++kept;
      EXPECT_EQ(l["method"], "raymarch");
    }
    if (l["rays"] != "quick") continue;
    ++quick;
    EXPECT_TRUE(l["method"] == "lut" && l["quality"] == "low") << l.dump();
    if (l["orders"] == "all" && l["band"] == "sun>=3") rmse_limit = l["rmse"];
  }
  EXPECT_EQ(kept, 1);
  // 5 bands, 2 orders, less single scattering at -12 degrees: darker than 1e-7 / sr on every quick ray.
  EXPECT_EQ(quick, 9);
  // The measured RMSE from the run's CSV (column all_orders_rel_rmse_sun_ge_3).
  std::ifstream csv(out / "accuracy-atmosphere.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  auto cells = [](const std::string& line) {  // CSV with quoted fields
    std::vector<std::string> out(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) out.emplace_back();
      else out.back() += c;
    }
    return out;
  };
  const std::vector<std::string> names = cells(header), values = cells(row);
  ASSERT_EQ(names.size(), values.size()) << header << "\n" << row;
  const auto column = std::find(names.begin(), names.end(), "all_orders_rel_rmse_sun_ge_3") - names.begin();
  ASSERT_LT(size_t(column), names.size()) << header;
  const double measured = std::stod(values[column]);
  EXPECT_NEAR(rmse_limit, measured * 1.15 + 0.001, 1e-4) << row;
  CliRun check = run(run_low + "--check --tolerances " + written.string() + " --out " + out.string());
  EXPECT_EQ(check.code, 0) << check.out;
  EXPECT_NE(check.out.find("0 of 9 limits exceeded"), std::string::npos) << check.out;
}

// `--panorama` draws the whole sky against the path tracer: one PNG per sun elevation, the three
// panels stacked (8-pixel cells, 4-pixel gaps), and its figures; a sun out of range or a grid over
// the bound is one error naming the option.
TEST(AtmosphereCli, PanoramaAgainstThePathTracer) {
  const fs::path out = tmp("panorama");
  CliRun r = run("accuracy atmosphere --panorama=-6,10 --panorama-size 3x2 --panorama-paths 4096 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* f : {"panorama-sun-6.png", "panorama-sun+10.png"}) {
    ASSERT_TRUE(fs::exists(out / f)) << f;
    const welkin::ImageU8 img = welkin::read_png((out / f).string());
    EXPECT_EQ(img.width, 3 * 8) << f;
    EXPECT_EQ(img.height, 3 * 2 * 8 + 2 * 4) << f;
  }
  EXPECT_NE(r.out.find("panorama, sun -6 deg (3x2 rays"), std::string::npos) << r.out;
  expect_one_line_error(run("accuracy atmosphere --panorama=-30 --out " + out.string()), "--panorama", "-18 to 90");
  expect_one_line_error(run("accuracy atmosphere --panorama 0 --panorama-size 1000x1 --out " + out.string()),
                        "--panorama-size", "360x90");
}

}  // namespace
