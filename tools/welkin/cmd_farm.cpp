// welkin farm slurm SCENE SEQUENCE --out DIR [--tasks N] [--partition P] [--time T] [--submit] [--resubmit]
//                   [--fps N] [--size WxH] [--from S] [--to S] [--exr] [--video out.mp4] [--contact-sheet f.png]
// welkin farm status DIR [--json]
//
// Welkin runs on a render farm rather than bringing its own: the farm's scheduler starts
// `welkin sequence --shard I/N` on its machines, and everything there is to know about a run's
// progress is in its frames folder (no daemon of ours).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <stdexcept>

#include "commands.h"
#include "program.h"
#include "run_folder.h"
#include "session.h"
#include "slurm_script.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/scene/json_fields.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kJobsFile = "jobs.json";  // in the slurm folder: the ids of the submitted jobs

struct FarmSlurmOptions {
  RunSettings run;
  std::string out_dir, partition, time, video, contact_sheet;
  int tasks = 4;
  bool submit = false, resubmit = false;
};

// The welkin the tasks run is this program, by absolute path: a batch job gets the PATH sbatch was
// called with, which may hold no welkin or another version of it; a path is also plain to see, and
// to edit where the cluster mounts the install elsewhere.
std::string this_program() {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error(ErrorInfo{.file = "/proc/self/exe", .message = "cannot find this program's own path: " + ec.message()});
  return self.string();
}

std::string absolute_or_empty(const std::string& path) {
  return path.empty() ? path : fs::absolute(path).lexically_normal().string();
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string describe_jobs(const nlohmann::json& jobs) {
  auto id = [&](const char* key) { return jobs.contains(key) && jobs[key].is_string() ? jobs[key].get<std::string>() : std::string("?"); };
  if (jobs.value("state", "") == "submitting") return "being submitted";
  return "render job " + id("render_job") + ", assembling job " + id("assemble_job");
}

nlohmann::json read_jobs(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return nullptr;
  return read_json_file(file.string());
}

void write_and_print(const SlurmFarm& farm, const std::string& name, const std::string& text) {
  const fs::path path = fs::path(farm.out_dir) / kSlurmFolder / name;
  write_file_atomically(path.string(), text);
  std::printf("==> %s <==\n%s\n", path.c_str(), text.c_str());
}

// Claims the folder's jobs file before sbatch runs, exclusively: of two submissions into one folder at
// once, one goes ahead. Returns whether this call created it (--resubmit goes ahead over an old one).
bool claim_submission(const fs::path& jobs_file, bool resubmit) {
  const bool claimed = create_file_exclusively(jobs_file.string(), R"({"state": "submitting"})" "\n");
  if (!claimed && !resubmit)
    throw Error(ErrorInfo{.file = jobs_file.string(),
                          .message = "jobs were already submitted for this folder (" + describe_jobs(read_jobs(jobs_file)) +
                                     "); `welkin farm status` shows their progress; pass --resubmit to submit again "
                                     "(frames already written are kept)"});
  return claimed;
}

int submit(const SlurmFarm& farm, const fs::path& jobs_file, bool claimed) {
  auto sbatch = [&](const std::string& script, const std::string& after) {
    const ProgramResult r = run_program(sbatch_arguments(farm, script, after), /*capture_output=*/true);
    const std::string id = parse_job_id(r.output);
    // Not bad input but a machine without Slurm, or Slurm saying no: a failure (exit 1), not exit 3.
    if (r.status < 0)
      throw std::runtime_error("sbatch is not installed (or not on PATH); the scripts are in " +
                               (fs::path(farm.out_dir) / kSlurmFolder).string() + ": submit them where Slurm is (see their first lines)");
    if (r.status != 0 || id.empty())
      throw std::runtime_error("sbatch refused " + script + " (exit status " + std::to_string(r.status) + ")");
    return id;
  };
  std::string render_id;
  try {
    render_id = sbatch("render.sbatch", "");
  } catch (const std::exception&) {
    if (claimed) fs::remove(jobs_file);  // nothing was submitted
    throw;
  }
  nlohmann::json jobs = {{"render_job", render_id}, {"tasks", farm.tasks}, {"submitted_utc", utc_now()}};
  try {
    jobs["assemble_job"] = sbatch("assemble.sbatch", render_id);
  } catch (const std::exception& e) {
    write_file_atomically(jobs_file.string(), jobs.dump(2) + "\n");
    throw std::runtime_error(std::string(e.what()) + "; the render job " + render_id +
                             " is submitted: submit slurm/assemble.sbatch by hand with --dependency=afterok:" + render_id);
  }
  write_file_atomically(jobs_file.string(), jobs.dump(2) + "\n");
  std::printf("submitted render job %s (%d tasks) and assembling job %s\n", render_id.c_str(), farm.tasks,
              jobs["assemble_job"].get<std::string>().c_str());
  return kOk;
}

int run_farm_slurm(const FarmSlurmOptions& o) {
  const RunManifest run = describe_run(o.run);
  check_assembly_options(run, o.video, o.contact_sheet);
  if (!o.partition.empty()) check_partition(o.partition);
  if (!o.time.empty()) check_time_limit(o.time);
  if (o.tasks > run.frames)
    throw Error(ErrorInfo{.path = "--tasks", .expected = "at most the run's " + std::to_string(run.frames) + " frames", .found = std::to_string(o.tasks)});
  const SlurmFarm farm{.run = run,
                       .welkin = this_program(),
                       .out_dir = absolute_or_empty(o.out_dir),
                       .tasks = o.tasks,
                       .partition = o.partition,
                       .time = o.time,
                       .contact_sheet = absolute_or_empty(o.contact_sheet),
                       .video = absolute_or_empty(o.video)};
  // The manifest now, so every task joins this run's folder and a folder of another run is refused here.
  join_run_folder(farm.out_dir, run, /*create=*/true);
  std::error_code ec;
  fs::create_directories(fs::path(farm.out_dir) / kSlurmFolder, ec);
  if (ec) throw Error(ErrorInfo{.file = (fs::path(farm.out_dir) / kSlurmFolder).string(), .message = "cannot create the folder: " + ec.message()});
  const bool submitting = o.submit || o.resubmit;
  const fs::path jobs_file = fs::path(farm.out_dir) / kSlurmFolder / kJobsFile;
  const bool claimed = submitting && claim_submission(jobs_file, o.resubmit);
  try {
    write_and_print(farm, "render.sbatch", render_script(farm));
    write_and_print(farm, "assemble.sbatch", assemble_script(farm));
  } catch (const std::exception&) {
    if (claimed) fs::remove(jobs_file);
    throw;
  }
  if (submitting) return submit(farm, jobs_file, claimed);
  std::printf("not submitted: pass --submit, or run sbatch from %s as the scripts' first lines say\n", farm.out_dir.c_str());
  return kOk;
}

// "3, 5-7" for frames 3, 5, 6, 7.
std::string frame_ranges(const std::vector<int>& frames) {
  std::string s;
  for (size_t i = 0; i < frames.size();) {
    size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    s += (s.empty() ? "" : ", ") + std::to_string(frames[i]) + (j > i ? "-" + std::to_string(frames[j]) : "");
    i = j + 1;
  }
  return s;
}

// The first line of a Slurm log that says its task failed: welkin's own error, or slurmstepd's
// (cancelled, over its time limit, out of memory).
std::string failure_in_log(const fs::path& log) {
  static const std::regex failure(R"(^(welkin: error:|slurmstepd(-\S+)?: error:).*)");
  std::string text;
  try {
    text = read_file_text(log.string(), 64ull << 20);
  } catch (const Error& e) {
    return std::string("cannot read the log: ") + e.what();
  }
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (std::regex_match(line, failure)) return line;
    start = end + 1;
  }
  return "";
}

int run_farm_status(const std::string& dir, bool json) {
  const std::optional<RunManifest> run = read_run_manifest(dir);
  if (!run)
    throw Error(ErrorInfo{.file = dir, .message = std::string("holds no ") + kRunManifestName +
                                                  ": not a frames folder of `welkin sequence` or `welkin farm slurm`"});
  std::vector<bool> done(size_t(run->frames), false);
  std::vector<int> missing;
  for (int i = 0; i < run->frames; ++i) done[size_t(i)] = fs::is_regular_file(fs::path(dir) / frame_file_name(i, run->exr));
  for (int i = 0; i < run->frames; ++i)
    if (!done[size_t(i)]) missing.push_back(i);
  // A temporary file of the atomic writer whose frame never appeared: its writer was stopped (or is
  // writing it right now).
  std::map<int, std::string> interrupted;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const int i = frame_of_temporary_file(e.path().filename().string(), run->exr);
    if (i >= 0 && i < run->frames && !done[size_t(i)]) interrupted[i] = e.path().filename().string();
  }
  // The logs of the jobs last submitted: those of earlier submissions no longer say how things stand.
  const fs::path slurm = fs::path(dir) / kSlurmFolder;
  const nlohmann::json jobs = read_jobs(slurm / kJobsFile);
  std::map<std::string, std::string> failed;  // log name -> its failure line
  if (jobs.is_object()) {
    const std::string render = jobs.value("render_job", ""), assemble = jobs.value("assemble_job", "");
    for (const auto& e : fs::directory_iterator(slurm, ec)) {
      const std::string name = e.path().filename().string();
      const bool ours = (!render.empty() && name.starts_with("render-" + render + "_") && name.ends_with(".log")) ||
                        (!assemble.empty() && name == "assemble-" + assemble + ".log");
      if (!ours) continue;
      if (std::string line = failure_in_log(e.path()); !line.empty()) failed[std::string(kSlurmFolder) + "/" + name] = line;
    }
  }
  const int done_count = run->frames - int(missing.size());
  if (json) {
    nlohmann::json j = {{"folder", dir}, {"frames", run->frames}, {"done", done_count}, {"missing", missing},
                        {"interrupted", nlohmann::json::array()}, {"failed", nlohmann::json::array()}, {"jobs", jobs}};
    for (const auto& [i, name] : interrupted) j["interrupted"].push_back({{"frame", i}, {"file", name}});
    for (const auto& [log, line] : failed) j["failed"].push_back({{"log", log}, {"error", line}});
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf("%s: %d frames of %s over %s (%s %s, %s fps, %s to %s s)\n", dir.c_str(), run->frames, run->scene.c_str(),
              run->sequence.c_str(), run->size.c_str(), run->exr ? "EXR" : "PNG", nlohmann::json(run->fps).dump().c_str(),
              nlohmann::json(run->from).dump().c_str(), nlohmann::json(run->to).dump().c_str());
  std::printf("done         %d of %d\n", done_count, run->frames);
  std::printf("missing      %zu%s\n", missing.size(), missing.empty() ? "" : (": " + frame_ranges(missing)).c_str());
  for (const auto& [i, name] : interrupted)
    std::printf("interrupted  frame %d: %s left by a write that stopped (or is running now)\n", i, name.c_str());
  for (const auto& [log, line] : failed) std::printf("failed       %s: %s\n", log.c_str(), line.c_str());
  if (jobs.is_object()) std::printf("jobs         %s\n", describe_jobs(jobs).c_str());
  return kOk;
}

}  // namespace

void add_farm_command(CLI::App& app, int& exit_code) {
  CLI::App* farm = app.add_subcommand("farm", "Render a sequence on a render farm (Slurm), and see how far it got");
  farm->require_subcommand(1);

  auto o = std::make_shared<FarmSlurmOptions>();
  CLI::App* slurm = farm->add_subcommand("slurm", "Write (and with --submit, submit) Slurm batch scripts rendering a sequence as a job array");
  slurm->add_option("scene", o->run.scene, "Scene file")->required()->check(CLI::ExistingFile);
  slurm->add_option("sequence", o->run.sequence, "Sequence file")->required()->check(CLI::ExistingFile);
  slurm->add_option("-o,--out", o->out_dir, "Folder for the frames (shared by the cluster's machines)")->required();
  add_run_options(*slurm, o->run);
  add_assembly_options(*slurm, o->video, o->contact_sheet);
  slurm->add_option("--tasks", o->tasks, "Array tasks, one shard of the frames each")->check(CLI::Range(1, kMaxSequenceFrames))->capture_default_str();
  slurm->add_option("--partition", o->partition, "Slurm partition (#SBATCH --partition)");
  slurm->add_option("--time", o->time, "Time limit of each job (#SBATCH --time), e.g. 2:00:00");
  slurm->add_flag("--submit", o->submit, "Submit the scripts with sbatch and print the job ids");
  slurm->add_flag("--resubmit", o->resubmit, "Submit (--submit) even though jobs were submitted for --out before (frames already written are kept)");
  slurm->callback([o, &exit_code] { exit_code = run_farm_slurm(*o); });

  auto dir = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* status = farm->add_subcommand("status", "What a frames folder holds: frames done, missing, failed tasks");
  status->add_option("dir", *dir, "Frames folder")->required();
  status->add_flag("--json", *json, "Machine-readable output");
  status->callback([dir, json, &exit_code] { exit_code = run_farm_status(*dir, *json); });
}

}  // namespace welkin::cli
