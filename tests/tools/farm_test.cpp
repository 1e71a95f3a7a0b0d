// Sharding, resuming and the Slurm scripts of `welkin sequence` and `welkin farm`, without GL:
// option parsing, frame selection, the run folder and the scripts run by a real bash.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include <unistd.h>

#include "run_folder.h"
#include "slurm_script.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;
using namespace welkin::cli;

// A file name in a scratch folder of this process.
fs::path tmp(const std::string& name) {
  return welkin::testing::scratch_folder("welkin-farm") / name;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const welkin::Error& e) {
    return e.what();
  }
  return "";
}

TEST(FarmOptions, ShardsAndFrameRangesParseStrictly) {
  EXPECT_EQ(parse_shard("0/4").index, 0);
  EXPECT_EQ(parse_shard("3/4").index, 3);
  EXPECT_EQ(parse_shard("3/4").count, 4);
  for (const char* bad : {"5/4", "4/4", "0/0", "-1/4", "1/-4", "+1/4", "a/4", "1/", "/4", "1/4x", " 1/4", "1/4 ", "1:4", "",
                          "99999999999999999999/4", "1/99999999999999999999", "1/100001", "1.0/4", "0x1/4"}) {
    const std::string e = error_of([&] { parse_shard(bad); });
    EXPECT_NE(e.find("--shard: expected I/N"), std::string::npos) << "'" << bad << "': " << e;
  }
  const FrameRange r = parse_frame_range("2:7");
  EXPECT_EQ(r.first, 2);
  EXPECT_EQ(r.last, 7);
  EXPECT_EQ(parse_frame_range("5:5").last, 5);
  for (const char* bad : {"9:3", "a:b", "1", "-1:3", "0:100000", "99999999999:1", "1:99999999999999999999", "3:", ":3", "1:2:3", "1 :2", ""}) {
    const std::string e = error_of([&] { parse_frame_range(bad); });
    EXPECT_NE(e.find("--frames: expected FIRST:LAST"), std::string::npos) << "'" << bad << "': " << e;
  }
}

TEST(FarmOptions, ShardsCoverTheRangeOnceAndSpreadOverIt) {
  for (int n : {1, 2, 3, 4, 7, 10}) {
    std::vector<int> all;
    for (int i = 0; i < n; ++i) {
      const std::vector<int> mine = select_frames(8, std::nullopt, Shard{i, n});
      EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
      all.insert(all.end(), mine.begin(), mine.end());
    }
    std::sort(all.begin(), all.end());
    EXPECT_EQ(all, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7})) << n << " shards";
  }
  EXPECT_EQ(select_frames(8, std::nullopt, Shard{1, 4}), (std::vector<int>{1, 5}));
  EXPECT_EQ(select_frames(8, FrameRange{2, 6}, Shard{1, 2}), (std::vector<int>{3, 5}));
  EXPECT_EQ(select_frames(8, FrameRange{2, 6}, std::nullopt), (std::vector<int>{2, 3, 4, 5, 6}));
  EXPECT_TRUE(select_frames(2, std::nullopt, Shard{3, 4}).empty()) << "more shards than frames: some get none";
  EXPECT_NE(error_of([] { select_frames(8, FrameRange{3, 8}, std::nullopt); }).find("--frames: expected frames within the run's 0 to 7"),
            std::string::npos);
}

RunManifest noon_run() {
  return describe_run(RunSettings{.scene = WELKIN_SOURCE_DIR "/assets/scenes/atmosphere-noon.json",
                                  .sequence = WELKIN_SOURCE_DIR "/assets/sequences/dawn-to-noon.json",
                                  .size = "64x36",
                                  .fps = 0.125});
}

TEST(FarmRunFolder, TheManifestIdentifiesARunByItsSettingsAndInputs) {
  const RunManifest run = noon_run();
  EXPECT_EQ(run.frames, 4);  // 24 s at 1/8 fps: 0, 8, 16, 24
  EXPECT_EQ(run.to, 24.0);
  EXPECT_TRUE(fs::path(run.scene).is_absolute());
  RunManifest other = run;
  other.scene = "/elsewhere/scene.json";
  EXPECT_TRUE(same_run(run, other)) << "a cluster may mount the inputs elsewhere";
  other = run;
  other.fps = 0.25;
  EXPECT_FALSE(same_run(run, other));
  // The same bytes under another name hash alike; one byte more does not.
  const fs::path copy = tmp("scene-copy.json");
  fs::copy_file(WELKIN_SOURCE_DIR "/assets/scenes/atmosphere-noon.json", copy, fs::copy_options::overwrite_existing);
  RunSettings s{.scene = copy.string(), .sequence = WELKIN_SOURCE_DIR "/assets/sequences/dawn-to-noon.json", .size = "64x36", .fps = 0.125};
  EXPECT_EQ(describe_run(s).inputs_hash, run.inputs_hash);
  std::ofstream(copy, std::ios::app) << " ";
  EXPECT_NE(describe_run(s).inputs_hash, run.inputs_hash);
}

TEST(FarmRunFolder, ShardsJoinAFolderOfTheirOwnRunOnly) {
  const RunManifest run = noon_run();
  const fs::path dir = tmp("join");
  fs::remove_all(dir);
  join_run_folder(dir.string(), run, /*create=*/false);
  EXPECT_FALSE(fs::exists(dir)) << "checking creates nothing";
  join_run_folder(dir.string(), run, /*create=*/true);
  ASSERT_TRUE(read_run_manifest(dir.string()));
  EXPECT_TRUE(same_run(*read_run_manifest(dir.string()), run));
  std::ofstream(dir / "frame_00000.png") << "x";
  join_run_folder(dir.string(), run, /*create=*/true);  // the same run again: fine
  RunManifest other = run;
  other.size = "32x18";
  EXPECT_NE(error_of([&] { join_run_folder(dir.string(), other, true); }).find("the folder holds frames of another run"), std::string::npos);
  const fs::path foreign = tmp("join-foreign");
  fs::create_directories(foreign);
  std::ofstream(foreign / "holiday.jpg") << "x";
  EXPECT_NE(error_of([&] { join_run_folder(foreign.string(), run, false); }).find("not empty and holds no welkin-run.json"), std::string::npos);
  std::ofstream(dir / kRunManifestName) << R"({"welkin_run": 1, "frames": "many"})";
  EXPECT_NE(error_of([&] { read_run_manifest(dir.string()); }).find("not a run manifest"), std::string::npos);
}

TEST(FarmRunFolder, OfManyShardsStartingAtOnceExactlyOneWritesTheManifest) {
  const fs::path file = tmp("exclusive.json");
  fs::remove(file);
  std::array<bool, 8> created{};
  std::vector<std::thread> threads;
  for (size_t i = 0; i < created.size(); ++i)
    threads.emplace_back([&, i] { created[i] = create_file_exclusively(file.string(), "writer " + std::to_string(i)); });
  for (auto& t : threads) t.join();
  ASSERT_EQ(std::count(created.begin(), created.end(), true), 1);
  const size_t winner = size_t(std::find(created.begin(), created.end(), true) - created.begin());
  EXPECT_EQ(welkin::read_file_text(file.string()), "writer " + std::to_string(winner));
  size_t leftovers = 0;
  for (const auto& e : fs::directory_iterator(file.parent_path()))
    leftovers += e.path().filename().string().starts_with("exclusive.json.") || e.path().filename().string().starts_with(".exclusive");
  EXPECT_EQ(leftovers, 0u) << "no private copies left behind";
}

TEST(FarmRunFolder, ShardsStartingAtOnceAllJoinOneFreshFolder) {
  const RunManifest run = noon_run();
  for (int round = 0; round < 20; ++round) {
    const fs::path dir = tmp("fresh-" + std::to_string(round));
    fs::remove_all(dir);
    std::array<std::string, 8> errors;
    std::vector<std::thread> shards;
    for (size_t i = 0; i < errors.size(); ++i)
      shards.emplace_back([&, i] { errors[i] = error_of([&] { join_run_folder(dir.string(), run, /*create=*/true); }); });
    for (auto& t : shards) t.join();
    for (const std::string& e : errors) EXPECT_EQ(e, "") << "round " << round;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{kRunManifestName});
  }
}

TEST(FarmRunFolder, TemporaryFilesOfTheWriterNameTheirFrame) {
  EXPECT_EQ(frame_of_temporary_file(".frame_00042.png.tmp-123-0-4567", false), 42);
  EXPECT_EQ(frame_of_temporary_file(".frame_00042.png.tmp-123-0-4567", true), -1);
  EXPECT_EQ(frame_of_temporary_file(".frame_00007.exr.tmp-9-1-2", true), 7);
  EXPECT_EQ(frame_of_temporary_file("frame_00042.png", false), -1);
  EXPECT_EQ(frame_of_temporary_file(".welkin-run.json.tmp-1-2-3", false), -1);
}

// Runs `command` in bash; its standard output.
std::string bash_output(const std::string& command) {
  const fs::path script = tmp("command.sh");
  std::ofstream(script) << command;
  FILE* p = popen(("bash " + script.string()).c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  pclose(p);
  return out;
}

const std::string kHostile = "a'b; rm -rf x $(touch pwned) `touch pwned` \"q\" \\ * ~ \n#SBATCH --x 'c'";

TEST(FarmSlurmScript, ShellQuotingKeepsEveryNameLiteral) {
  EXPECT_EQ(shell_quote("a'b; rm -rf x"), "'a'\\''b; rm -rf x'");
  EXPECT_EQ(shell_quote("/plain/path_1.json"), "/plain/path_1.json");
  EXPECT_EQ(shell_quote(""), "''");
  const fs::path cwd = tmp("quoting");
  fs::create_directories(cwd);
  for (const std::string& name : {kHostile, std::string("'"), std::string("''"), std::string("-n"), std::string("$HOME"), std::string("a\tb")}) {
    const std::string out = bash_output("cd " + shell_quote(cwd.string()) + " && printf '%s' " + shell_quote(name));
    EXPECT_EQ(out, name);
  }
  EXPECT_FALSE(fs::exists(cwd / "pwned")) << "a name ran as a command";
}

// A farm in a scratch folder of its own, every name in it hostile.
SlurmFarm hostile_farm(const std::string& folder) {
  const fs::path root = tmp(folder);
  fs::create_directories(root);
  RunManifest run = noon_run();
  run.scene = (root / ("scene " + kHostile + ".json")).string();
  run.sequence = (root / "seq'uence.json").string();
  return SlurmFarm{.run = run,
                   .welkin = (root / "fake welkin's").string(),
                   .out_dir = (root / ("frames " + kHostile)).string(),
                   .tasks = 4,
                   .partition = "debug",
                   .time = "0:10:00",
                   .contact_sheet = (root / "sheet;$(touch pwned).png").string(),
                   .video = ""};
}

// The fake welkin records its arguments, one per file (a name may hold a newline).
std::vector<std::string> run_script_with_fake_welkin(const SlurmFarm& farm, const std::string& script) {
  const fs::path root = fs::path(farm.welkin).parent_path();
  const fs::path args = root / "args";
  fs::remove_all(args);
  fs::create_directories(args);
  std::ofstream(farm.welkin) << "#!/bin/bash\ni=0\nfor a in \"$@\"; do printf '%s' \"$a\" > " + shell_quote(args.string()) +
                                    "/$i; i=$((i+1)); done\n";
  fs::permissions(farm.welkin, fs::perms::owner_all);
  const fs::path file = root / "job.sbatch";
  std::ofstream(file) << script;
  bash_output("cd " + shell_quote(root.string()) + " && SLURM_ARRAY_TASK_ID=2 bash " + shell_quote(file.string()));
  std::vector<std::string> argv;
  for (int i = 0; fs::exists(args / std::to_string(i)); ++i) argv.push_back(welkin::read_file_text((args / std::to_string(i)).string()));
  return argv;
}

TEST(FarmSlurmScript, TheRenderScriptRunsOneShardPerArrayTaskWithNamesLiteral) {
  const SlurmFarm farm = hostile_farm("script-run");
  const std::string script = render_script(farm);
  EXPECT_NE(script.find("#SBATCH --array=0-3\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --partition=debug\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --time=0:10:00\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=slurm/render-%A_%a.log\n"), std::string::npos);
  const std::vector<std::string> argv = run_script_with_fake_welkin(farm, script);
  const std::vector<std::string> expected{"sequence", farm.run.scene, farm.run.sequence, "--out", farm.out_dir, "--fps", "0.125",
                                          "--size", "64x36", "--from", "0.0", "--to", "24.0", "--shard", "2/4", "--resume"};
  EXPECT_EQ(argv, expected);
  EXPECT_FALSE(fs::exists(tmp("script-run") / "pwned"));
  // sbatch reads #SBATCH lines up to the first command; there, only the script's own (a name with a
  // newline and "#SBATCH" in it comes after, inside quotes).
  const std::string head = script.substr(0, script.find("\nset -euo pipefail\n"));
  size_t directives = 0;
  for (size_t at = head.find("\n#SBATCH"); at != std::string::npos; at = head.find("\n#SBATCH", at + 1)) ++directives;
  EXPECT_EQ(directives, 6u) << script;
  EXPECT_EQ(head.find(farm.out_dir), std::string::npos) << "no file name before the first command";
}

TEST(FarmSlurmScript, TheAssemblingScriptFinishesTheWholeRunAndWritesTheSheet) {
  const SlurmFarm farm = hostile_farm("script-assemble");
  const std::string script = assemble_script(farm);
  EXPECT_NE(script.find("#SBATCH --kill-on-invalid-dep=yes\n"), std::string::npos) << script;
  const std::vector<std::string> argv = run_script_with_fake_welkin(farm, script);
  ASSERT_GE(argv.size(), 3u);
  EXPECT_EQ(std::vector<std::string>(argv.end() - 3, argv.end()), (std::vector<std::string>{"--resume", "--contact-sheet", farm.contact_sheet}));
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--shard"), 0);
  EXPECT_FALSE(fs::exists(tmp("script-assemble") / "pwned"));
  const std::vector<std::string> sbatch = sbatch_arguments(farm, "assemble.sbatch", "41");
  EXPECT_EQ(sbatch, (std::vector<std::string>{"sbatch", "--parsable", "--chdir=" + farm.out_dir, "--dependency=afterok:41",
                                              farm.out_dir + "/slurm/assemble.sbatch"}));
}

TEST(FarmSlurmScript, PartitionsTimesAndJobIdsAreChecked) {
  check_partition("gpu,debug_2");
  check_time_limit("2:00:00");
  check_time_limit("1-12");
  check_time_limit("30");
  check_time_limit("UNLIMITED");
  for (const char* bad : {"", "a b", "gpu\n#SBATCH --uid=0", "x;y", "'q'"})
    EXPECT_NE(error_of([&] { check_partition(bad); }).find("--partition"), std::string::npos) << bad;
  for (const char* bad : {"", "2h", "1:00:00\n#SBATCH --x", "-1", "1::2", "tomorrow"})
    EXPECT_NE(error_of([&] { check_time_limit(bad); }).find("--time"), std::string::npos) << bad;
  EXPECT_EQ(parse_job_id("123\n"), "123");
  EXPECT_EQ(parse_job_id("123;cluster\n"), "123");
  EXPECT_EQ(parse_job_id(""), "");
  EXPECT_EQ(parse_job_id("sbatch: error: invalid partition\n"), "");
}

}  // namespace
