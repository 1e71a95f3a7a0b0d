// The `welkin` program as a user runs it: exit codes, one-line errors, outputs.
#include <gtest/gtest.h>

#include "cli_run.h"
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "welkin/core/files.h"
#include "welkin/gfx/image.h"

namespace {

namespace fs = std::filesystem;

using welkin::testing::CliRun;

CliRun run(const std::string& args, bool with_stderr = true) { return welkin::testing::run_welkin(args, with_stderr); }

fs::path tmp(const std::string& name) { return welkin::testing::scratch_path("welkin-cli", name); }

TEST(WelkinCli, RenderWritesARealImage) {
  fs::path out = tmp("debug.png");
  CliRun r = run("render " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --size 96x54 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("wrote " + out.string()), std::string::npos);
  welkin::ImageU8 img = welkin::read_png(out.string());
  EXPECT_EQ(img.width, 96);
  // Not blank: sky above, ground below.
  const uint8_t* sky = img.pixel(48, 2);
  const uint8_t* ground = img.pixel(48, 52);
  EXPECT_GT(sky[2], sky[0]) << "the sky is blue";
  EXPECT_LT(ground[2], sky[2]);
}

TEST(WelkinCli, RenderJsonReportsPassesAndExrIsHdr) {
  fs::path out = tmp("debug.exr");
  CliRun r = run("render " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --size 32x18 --json --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["passes"].size(), 4u);
  EXPECT_EQ(j["modules"], nlohmann::json::array({"core"}));
  welkin::ImageF hdr = welkin::read_exr(out.string());
  EXPECT_GT(hdr.pixel(16, 1)[2], 1000.0f) << "linear radiance, not display values";
}

TEST(WelkinCli, MalformedSceneExitsNonZeroWithOneClearLine) {
  fs::path bad = tmp("typo.json");
  std::ofstream(bad) << R"({"welkin_scene": 1, "entities": [{"components": {"core.Camera": {"vertical_fov_dg": 50}}}]})";
  CliRun r = run("render " + bad.string() + " --out " + tmp("never.png").string());
  EXPECT_FALSE(r.signaled) << "no crash";
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find(bad.string() + ": at /entities/0/components/core.Camera/vertical_fov_dg: unknown field"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(tmp("never.png")));
}

TEST(WelkinCli, TruncatedSceneAndBadOptions) {
  fs::path bad = tmp("truncated.json");
  std::ofstream(bad) << R"({"welkin_scene": 1, "entities": [)";
  CliRun r = run("render " + bad.string());
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find("truncated"), std::string::npos) << r.out;
  r = run("render " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --size 0x10");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find("--size"), std::string::npos) << r.out;
  r = run("render " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --out x.jpg");
  EXPECT_EQ(r.code, 3);
  r = run("render --set core.Camera/vertical_fov_deg=nan " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --out " + tmp("nan.png").string());
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find("core.Camera/vertical_fov_deg"), std::string::npos) << r.out;
  r = run("frobnicate");
  EXPECT_EQ(r.code, 2);
  r = run("render --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--timings"), std::string::npos);
}

TEST(WelkinCli, InfoListsModulesAndWhatASceneLoads) {
  CliRun r = run("info --modules --json " WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  ASSERT_EQ(r.code, 0) << r.out;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scene_modules"], nlohmann::json::array({"core"}));
  bool has_core = false;
  for (const auto& m : j["available_modules"]) has_core = has_core || m["name"] == "core";
  EXPECT_TRUE(has_core);
}

TEST(WelkinCli, InfoShowsWhatEachModuleDependsOnAndUses) {
  CliRun r = run("info --modules --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json info = nlohmann::json::parse(r.out);
  std::map<std::string, nlohmann::json> modules;
  for (const auto& m : info["available_modules"]) modules[m["name"].get<std::string>()] = m;
  ASSERT_TRUE(modules.count("godrays") && modules.count("clouds")) << r.out;
  EXPECT_EQ(modules["godrays"]["depends"], nlohmann::json::array({"atmosphere"}));
  EXPECT_EQ(modules["clouds"]["depends"], nlohmann::json::array());
  EXPECT_EQ(modules["clouds"]["uses"], nlohmann::json::array({"atmosphere", "timeofday"}));
  EXPECT_EQ(modules["timeofday"]["uses"], nlohmann::json::array());
  r = run("info --modules");
  EXPECT_NE(r.out.find("depends on: atmosphere\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("uses: atmosphere, timeofday\n"), std::string::npos) << r.out;
}

TEST(WelkinCli, SunJsonHasTheDocumentedKeysAndTheSpaValues) {
  CliRun r = run("sun --lat 39.742476 --lon -105.1786 --utc 2003-10-17T12:30:30-07:00 --elevation-m 1830.14 "
                 "--pressure-mbar 820 --temperature-c 11 --delta-t 67 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["sun"]["zenith_deg"].get<double>(), 50.11162, 1e-3);  // Reda & Andreas 2004, table A5.1
  EXPECT_NEAR(j["sun"]["azimuth_deg"].get<double>(), 194.34024, 1e-3);
  EXPECT_NEAR(j["sun"]["elevation_deg"].get<double>(), 90 - 50.11162, 1e-3);
  for (const char* k : {"azimuth_deg", "elevation_deg", "ra_deg", "dec_deg", "distance_km", "illuminated_fraction"})
    EXPECT_TRUE(j["moon"].contains(k)) << k;
  EXPECT_EQ(j["sun_visible_fraction"], 1.0);
  r = run("sun --lat 95 --lon 0 --utc 2003-10-17T12:30:30Z");
  EXPECT_EQ(r.code, 3) << r.out;
  r = run("sun --lat 10 --lon 0 --utc 2003-02-30T12:00:00Z");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("--utc"), std::string::npos) << r.out;
}

TEST(WelkinCli, SequenceRendersFramesThatGoFromNightToDay) {
  fs::path dir = tmp("frames");
  fs::path sheet = tmp("sheet.png");
  CliRun r = run("sequence " WELKIN_SOURCE_DIR "/assets/scenes/flight.json " WELKIN_SOURCE_DIR
                 "/assets/sequences/dawn-to-noon.json --fps 0.125 --size 32x18 --out " + dir.string() +
                 " --contact-sheet " + sheet.string());
  ASSERT_EQ(r.code, 0) << r.out;
  auto mean = [](const welkin::ImageU8& img) {
    double s = 0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) s += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
    return s / (img.rgba.size() / 4 * 3);
  };
  double night = mean(welkin::read_png((dir / "frame_00000.png").string()));
  double day = mean(welkin::read_png((dir / "frame_00003.png").string()));
  EXPECT_LT(night, 30.0);
  EXPECT_GT(day, 80.0);
  EXPECT_TRUE(fs::exists(sheet));
  fs::path bad = tmp("bad-sequence.json");
  std::ofstream(bad) << R"({"welkin_sequence": 1, "tracks": [{"target": "core.Camera/fov", "keys": [{"t": 0, "value": 1}]}]})";
  r = run("sequence " WELKIN_SOURCE_DIR "/assets/scenes/flight.json " + bad.string() + " --size 8x8 --out " + dir.string());
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find(bad.string() + ": at /tracks/0"), std::string::npos) << r.out;
}

// Shell quoting for the test's own command line (run_welkin goes through popen).
std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

TEST(WelkinCli, SequenceVideoPassesFileNamesToFfmpegLiterally) {
  // A stand-in ffmpeg on PATH that records its arguments, one a line.
  fs::path bin = tmp("fake-bin");
  fs::create_directories(bin);
  fs::path args_file = tmp("ffmpeg-args.txt");
  fs::path injected = tmp("injected");
  fs::remove(args_file);
  fs::remove(injected);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\nprintf '%s\\n' \"$@\" > " + args_file.string() + "\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (bin.string() + ":" + old_path).c_str(), 1);

  const std::string video = tmp("v';touch " + injected.string() + ";'$(touch " + injected.string() + ").mp4").string();
  CliRun r = run("sequence " WELKIN_SOURCE_DIR "/assets/scenes/flight.json " WELKIN_SOURCE_DIR
                 "/assets/sequences/dawn-to-noon.json --fps 0.125 --size 8x8 --out " + tmp("video-frames").string() +
                 " --video " + shell_quoted(video));
  setenv("PATH", old_path.c_str(), 1);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists(injected)) << "the file name ran a shell command";
  std::ifstream args(args_file);
  std::string line, last;
  while (std::getline(args, line)) last = line;
  EXPECT_EQ(last, video) << "ffmpeg's last argument is the output file, unchanged";
}

// The benchmark divides each frame by a copy timed right after it, and runs only what changed: with
// a still camera and sun the per-frame LUTs are kept, a turning camera rebuilds the aerial
// perspective (it follows the view) but not the sky-view LUT (laid out around the camera's position).
TEST(WelkinCli, BenchReportsRatiosAndRunsOnlyWhatChanged) {
  auto passes_of = [](const CliRun& r) {
    std::set<std::string> names;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    for (const auto& p : report["passes"]) names.insert(p["name"].get<std::string>());
    return names;
  };
  const std::string scene = WELKIN_SOURCE_DIR "/assets/scenes/atmosphere-noon.json --size 32x18 --frames 3 --json";
  CliRun still = run("bench " + scene, false);
  ASSERT_EQ(still.code, 0) << still.out;
  const auto j = nlohmann::json::parse(still.out);
  EXPECT_GT(j["copy_floor_ms"].get<double>(), 0.0);
  EXPECT_GT(j["frame_ratio_to_copy"].get<double>(), 1.0) << "a frame costs more than one copy";
  EXPECT_FALSE(passes_of(still).count("atmosphere.sky_view"));
  EXPECT_FALSE(passes_of(still).count("atmosphere.aerial_perspective"));
  // The CPU's share of a frame (without its waits for the GPU) is within the frame's finished time.
  EXPECT_GT(j["cpu_frame_median_ms"].get<double>(), 0.0);
  EXPECT_LE(j["cpu_frame_median_ms"].get<double>(), j["frame_median_ms"].get<double>());
  // The full-screen passes' form: measured for the device, or forced for a comparison.
  EXPECT_EQ(j["pass_form"]["used"], j["pass_form"]["measured"]);
  EXPECT_GT(j["pass_form"]["probe_fragment_ms"].get<double>(), 0.0);
  EXPECT_GT(j["pass_form"]["probe_compute_ms"].get<double>(), 0.0);
  CliRun compute = run("bench " + scene + " --form compute", false);
  ASSERT_EQ(compute.code, 0) << compute.out;
  EXPECT_EQ(nlohmann::json::parse(compute.out)["pass_form"]["used"], "compute");
  EXPECT_NE(run("bench " + scene + " --form vertex").code, 0);
  CliRun turning = run("bench " + scene + " --turn-deg 2", false);
  ASSERT_EQ(turning.code, 0) << turning.out;
  EXPECT_FALSE(passes_of(turning).count("atmosphere.sky_view"));
  EXPECT_TRUE(passes_of(turning).count("atmosphere.aerial_perspective"));
  EXPECT_NE(run("bench " + scene + " --turn-deg 400").code, 0);
}

#define WELKIN_FLIGHT WELKIN_SOURCE_DIR "/assets/scenes/flight.json "
#define WELKIN_DAWN WELKIN_SOURCE_DIR "/assets/sequences/dawn-to-noon.json "

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(WelkinCli, SequenceNeverMixesFramesOfTwoRuns) {
  fs::path dir = tmp("two-runs");
  fs::remove_all(dir);
  // 24 s at 1/8 fps: frames 0..3.
  CliRun r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 0.125 --size 8x8 --out " + dir.string());
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(names_in(dir).size(), 5u) << "4 frames and the run's manifest";
  std::ofstream(dir / "notes.txt") << "mine";
  // A second, shorter run would leave frames 2 and 3 of the first one for ffmpeg to pick up.
  r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 0.0625 --size 8x8 --out " + dir.string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find(dir.string() + ": the output folder is not empty"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--overwrite"), std::string::npos) << r.out;
  EXPECT_EQ(names_in(dir).size(), 6u) << "a refused run changes nothing";
  // --overwrite removes this command's own frames (and manifest) only.
  r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 0.0625 --size 8x8 --overwrite --out " + dir.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "notes.txt", "welkin-run.json"}));
  EXPECT_NE(welkin::read_file_text((dir / "welkin-run.json").string()).find("\"fps\": 0.0625"), std::string::npos);
}

std::string bytes_of(const fs::path& file) { return welkin::read_file_text(file.string()); }

// 24 s at 1/4 fps: frames 0..6, at 16x9.
#define WELKIN_SEVEN WELKIN_FLIGHT WELKIN_DAWN "--fps 0.25 --size 16x9 "

TEST(WelkinCli, ShardsAndFrameRangesTogetherEqualOneRunByteForByte) {
  const fs::path whole = tmp("shards-whole"), sharded = tmp("shards-sharded"), ranged = tmp("shards-ranged");
  for (const fs::path& d : {whole, sharded, ranged}) fs::remove_all(d);
  CliRun r = run("sequence " WELKIN_SEVEN "--out " + whole.string());
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(names_in(whole).size(), 8u);
  // Three shards into one folder (in reverse order: order must not matter), and two ranges.
  for (const char* shard : {"2/3", "1/3", "0/3"}) {
    r = run("sequence " WELKIN_SEVEN "--out " + sharded.string() + " --shard " + shard);
    ASSERT_EQ(r.code, 0) << shard << ": " << r.out;
  }
  for (const char* range : {"4:6", "0:3"}) {
    r = run("sequence " WELKIN_SEVEN "--out " + ranged.string() + " --frames " + range);
    ASSERT_EQ(r.code, 0) << range << ": " << r.out;
  }
  EXPECT_EQ(names_in(sharded), names_in(whole));
  EXPECT_EQ(names_in(ranged), names_in(whole));
  for (const std::string& name : names_in(whole)) {
    if (name == "welkin-run.json") continue;
    EXPECT_EQ(bytes_of(sharded / name), bytes_of(whole / name)) << name;
    EXPECT_EQ(bytes_of(ranged / name), bytes_of(whole / name)) << name;
  }
  // A shard of another run (another size) is refused, and writes nothing.
  r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 0.25 --size 16x8 --out " + sharded.string() + " --shard 0/3");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("the folder holds frames of another run"), std::string::npos) << r.out;
  EXPECT_EQ(bytes_of(sharded / "frame_00000.png"), bytes_of(whole / "frame_00000.png"));
  // A folder of somebody else's files is no shard's folder.
  const fs::path foreign = tmp("shards-foreign");
  fs::create_directories(foreign);
  std::ofstream(foreign / "thesis.tex") << "mine";
  r = run("sequence " WELKIN_SEVEN "--out " + foreign.string() + " --shard 0/2");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_EQ(names_in(foreign), (std::vector<std::string>{"thesis.tex"}));
}

TEST(WelkinCli, ResumeRendersOnlyWhatIsMissingAndNeverTrustsAnInterruptedWrite) {
  const fs::path dir = tmp("resume"), reference = tmp("resume-reference");
  fs::remove_all(dir);
  fs::remove_all(reference);
  ASSERT_EQ(run("sequence " WELKIN_SEVEN "--out " + reference.string()).code, 0);
  CliRun r = run("sequence " WELKIN_SEVEN "--out " + dir.string() + " --frames 0:3");
  ASSERT_EQ(r.code, 0) << r.out;
  // Frame 4's write was interrupted: only its temporary file is there. Frame 1 is marked so a
  // re-render would show.
  std::ofstream(dir / ".frame_00004.png.tmp-999-0-1") << "half a PNG";
  std::ofstream(dir / "frame_00001.png") << "kept as written";
  r = run("sequence " WELKIN_SEVEN "--out " + dir.string() + " --resume");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("wrote 3 frames to " + dir.string() + " (4 of them already there)"), std::string::npos) << r.out;
  EXPECT_EQ(bytes_of(dir / "frame_00001.png"), "kept as written") << "a finished frame is skipped";
  for (const char* name : {"frame_00004.png", "frame_00005.png", "frame_00006.png"})
    EXPECT_EQ(bytes_of(dir / name), bytes_of(reference / name)) << name;
  // The status names what is done, missing and interrupted.
  fs::remove(dir / "frame_00005.png");
  fs::remove(dir / "frame_00004.png");
  r = run("farm status " + dir.string(), false);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("done         5 of 7"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("missing      2: 4-5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("interrupted  frame 4: .frame_00004.png.tmp-999-0-1"), std::string::npos) << r.out;
  // A whole run without --resume still refuses the folder.
  r = run("sequence " WELKIN_SEVEN "--out " + dir.string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("--resume"), std::string::npos) << r.out;
}

TEST(WelkinCli, BadShardsAndRangesAreOneClearError) {
  const fs::path dir = tmp("bad-shards");
  fs::remove_all(dir);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--shard 5/4", "--shard: expected I/N"},         {"--shard 0/0", "--shard: expected I/N"},
      {"--shard 4/4", "--shard: expected I/N"},         {"--shard x/4", "--shard: expected I/N"},
      {"--shard 1/99999999999999999999", "--shard"},    {"--frames 9:3", "--frames: expected FIRST:LAST"},
      {"--frames 1:x", "--frames: expected FIRST:LAST"}, {"--frames 0:99999999999", "--frames"},
      {"--frames 3:7", "--frames: expected frames within the run's 0 to 6"},
      {"--shard 0/2 --contact-sheet " + tmp("s.png").string(), "--contact-sheet: needs every frame"},
      {"--frames 0:1 --video " + tmp("v.mp4").string(), "--video: needs every frame"},
      {"--shard 0/2 --overwrite", "--overwrite: cannot be combined with --shard or --resume"}};
  for (const auto& [options, message] : cases) {
    CliRun r = run("sequence " WELKIN_SEVEN "--out " + dir.string() + " " + options);
    EXPECT_FALSE(r.signaled) << options;
    EXPECT_EQ(r.code, 3) << options << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << options << ": " << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << options << ": " << r.out;
  }
  EXPECT_FALSE(fs::exists(dir)) << "nothing was written";
  for (const std::string& options : {std::string("--tasks 9"), std::string("--tasks 0"), std::string("--partition 'a b'"),
                                     std::string("--time soon"), std::string("--exr --video ") + tmp("v.mp4").string()}) {
    CliRun r = run("farm slurm " WELKIN_SEVEN "--out " + dir.string() + " " + options);
    EXPECT_NE(r.code, 0) << options << ": " << r.out;
    EXPECT_NE(r.code, 1) << options << ": " << r.out;
  }
  CliRun r = run("farm status " + tmp("no-such-folder").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("holds no welkin-run.json"), std::string::npos) << r.out;
}

TEST(WelkinCli, FarmSlurmSubmitsOnceThroughSbatchWithLiteralNames) {
  // A stand-in sbatch on PATH: records its arguments (one file each) and answers with job ids.
  const fs::path bin = tmp("fake-sbatch-bin"), calls = tmp("sbatch-calls");
  fs::remove_all(calls);
  fs::create_directories(bin);
  fs::create_directories(calls);
  std::ofstream(bin / "sbatch") << "#!/bin/bash\nn=$(ls " + calls.string() + " | wc -l)\nmkdir " + calls.string() +
                                       "/$n\ni=0\nfor a in \"$@\"; do printf '%s' \"$a\" > " + calls.string() +
                                       "/$n/$i; i=$((i+1)); done\necho \"$((41 + n));cluster\"\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const fs::path dir = tmp("farm it's; $(touch pwned)");
  fs::remove_all(dir);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (bin.string() + ":" + old_path).c_str(), 1);
  const std::string command = "farm slurm " WELKIN_SEVEN "--tasks 3 --out " + shell_quoted(dir.string());
  CliRun r = run(command + " --submit", false);
  CliRun again = run(command + " --submit");
  CliRun resubmit = run(command + " --resubmit", false);
  setenv("PATH", bin.string().c_str(), 1);  // no sbatch: only the fake one's folder, emptied
  fs::remove(bin / "sbatch");
  CliRun missing = run("farm slurm " WELKIN_SEVEN "--tasks 3 --submit --out " + tmp("farm-no-sbatch").string());
  setenv("PATH", old_path.c_str(), 1);

  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("#SBATCH --array=0-2"), std::string::npos) << "the scripts are printed: " << r.out;
  EXPECT_NE(r.out.find("submitted render job 41 (3 tasks) and assembling job 42"), std::string::npos) << r.out;
  auto arg = [&](int call, int i) { return bytes_of(calls / std::to_string(call) / std::to_string(i)); };
  EXPECT_EQ(arg(0, 0), "--parsable");
  EXPECT_EQ(arg(0, 1), "--chdir=" + dir.string());
  EXPECT_EQ(arg(0, 2), (dir / "slurm/render.sbatch").string());
  EXPECT_EQ(arg(1, 2), "--dependency=afterok:41");
  EXPECT_EQ(arg(1, 3), (dir / "slurm/assemble.sbatch").string());
  EXPECT_FALSE(fs::exists(tmp("pwned")));
  EXPECT_FALSE(fs::exists("pwned"));
  // Not twice, unless asked.
  EXPECT_EQ(again.code, 3) << again.out;
  EXPECT_NE(again.out.find("jobs were already submitted for this folder (render job 41, assembling job 42)"), std::string::npos) << again.out;
  ASSERT_EQ(resubmit.code, 0) << resubmit.out;
  EXPECT_NE(resubmit.out.find("submitted render job 43 (3 tasks) and assembling job 44"), std::string::npos) << resubmit.out;
  EXPECT_EQ(names_in(calls).size(), 4u) << "the refused submission ran no sbatch";
  const nlohmann::json jobs = nlohmann::json::parse(bytes_of(dir / "slurm/jobs.json"));
  EXPECT_EQ(jobs["render_job"], "43");
  EXPECT_EQ(jobs["assemble_job"], "44");
  // Status reads the folder: no frames yet, the last jobs, and a task log that says it failed.
  std::ofstream(dir / "slurm/render-43_1.log") << "frame 1/3\nwelkin: error: out of memory\n";
  std::ofstream(dir / "slurm/render-41_2.log") << "slurmstepd: error: *** JOB 41 CANCELLED ***\n";  // an earlier submission
  CliRun status = run("farm status " + shell_quoted(dir.string()), false);
  ASSERT_EQ(status.code, 0) << status.out;
  EXPECT_NE(status.out.find("done         0 of 7"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("missing      7: 0-6"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("failed       slurm/render-43_1.log: welkin: error: out of memory"), std::string::npos) << status.out;
  EXPECT_EQ(status.out.find("render-41_2"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("jobs         render job 43, assembling job 44"), std::string::npos) << status.out;
  // Without sbatch: one clear line, exit 1, and nothing recorded as submitted.
  EXPECT_EQ(missing.code, 1) << missing.out;
  EXPECT_NE(missing.out.find("welkin: error: sbatch is not installed"), std::string::npos) << missing.out;
  EXPECT_FALSE(fs::exists(tmp("farm-no-sbatch") / "slurm/jobs.json"));
  EXPECT_TRUE(fs::exists(tmp("farm-no-sbatch") / "slurm/render.sbatch"));
}

TEST(WelkinCli, FrameCountsAndImageSizesAreCheckedBeforeUse) {
  // 1e7 s at 1000 fps is 1e10 frames: more than an int holds, and more than any run should render.
  CliRun r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 1000 --to 10000000 --size 8x8 --out " +
                 tmp("many").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("at most 100000 frames"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(tmp("many") / "frame_00000.png"));
  // The same from a file: a sequence claiming 1e300 seconds.
  fs::path endless = tmp("endless.json");
  std::ofstream(endless) << R"({"welkin_sequence": 1, "duration_s": 1e300, "tracks": []})";
  r = run("sequence " WELKIN_FLIGHT + endless.string() + " --size 8x8 --out " + tmp("endless").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find(endless.string() + ": at /duration_s: expected 0 to 1e7 seconds"), std::string::npos) << r.out;
  // 16384 x 16384 is within the per-side bound but 4 GiB of float readback: refused before rendering.
  r = run("render " WELKIN_FLIGHT "--size 16384x16384 --out " + tmp("huge.png").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("--size: expected 1..16384 per side and at most 67108864 pixels"), std::string::npos) << r.out;
  // A contact sheet of four 8000-pixel-wide frames side by side is refused before any frame is rendered.
  r = run("sequence " WELKIN_FLIGHT WELKIN_DAWN "--fps 0.125 --size 8000x8 --out " + tmp("wide").string() +
          " --contact-sheet " + tmp("wide.png").string());
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("--contact-sheet: expected a sheet of at most 16384 pixels a side"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(tmp("wide") / "frame_00000.png"));
}

TEST(WelkinCli, AMalformedModuleManifestIsReportedNotFatal) {
  fs::path dir = tmp("bad-modules");
  fs::create_directories(dir);
  std::ofstream(dir / "zzz.module.json") << "{ not json";
  setenv("WELKIN_MODULE_PATH", dir.c_str(), 1);
  CliRun r = run("render " WELKIN_SOURCE_DIR "/assets/scenes/debug.json --size 16x16 --out " + tmp("despite.png").string());
  CliRun info = run("info --modules --json", /*with_stderr=*/false);
  unsetenv("WELKIN_MODULE_PATH");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("skipped module manifest: " + (dir / "zzz.module.json").string()), std::string::npos) << r.out;
  ASSERT_EQ(info.code, 0) << info.out;
  nlohmann::json j = nlohmann::json::parse(info.out);
  ASSERT_EQ(j["skipped_manifests"].size(), 1u) << info.out;
  EXPECT_FALSE(j["available_modules"].empty());
}

}  // namespace
