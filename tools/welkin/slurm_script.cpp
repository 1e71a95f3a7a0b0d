#include "slurm_script.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "welkin/core/error.h"

namespace welkin::cli {

namespace {

// A number as `welkin sequence` reads it back to the same double (shards must agree on every time).
std::string exact(double v) { return nlohmann::json(v).dump(); }

std::string header(const std::string& what) {
  return "#!/bin/bash\n" + what +
                  "# Written by `welkin farm slurm`; edit the #SBATCH lines (partition, time, memory) as your cluster needs.\n"
                  "# Submit from the frames folder (Slurm's logs are written relative to it, into slurm/):\n"
                  "#   sbatch --parsable slurm/render.sbatch\n"
                  "#   sbatch --parsable --dependency=afterok:<the render job's id> slurm/assemble.sbatch\n"
                  "# or let `welkin farm slurm ... --submit` do both. Progress: welkin farm status <frames folder>\n";
}

std::string resources(const SlurmFarm& farm) {
  std::string s = "#SBATCH --ntasks=1\n";
  if (!farm.partition.empty()) s += "#SBATCH --partition=" + farm.partition + "\n";
  if (!farm.time.empty()) s += "#SBATCH --time=" + farm.time + "\n";
  return s;
}

// The `welkin sequence` command line every job of the farm shares: the run, exactly as resolved here.
std::string sequence_command(const SlurmFarm& farm) {
  const RunManifest& r = farm.run;
  return "set -euo pipefail\n"
         "# The welkin that wrote this script (any install of the same version renders the same frames).\n"
         "welkin=" + shell_quote(farm.welkin) + "\n"
         "exec \"$welkin\" sequence \\\n"
         "  " + shell_quote(r.scene) + " \\\n"
         "  " + shell_quote(r.sequence) + " \\\n"
         "  --out " + shell_quote(farm.out_dir) + " \\\n"
         "  --fps " + exact(r.fps) + " --size " + shell_quote(r.size) + " --from " + exact(r.from) + " --to " + exact(r.to) +
         (r.exr ? " --exr" : "");
}

}  // namespace

std::string shell_quote(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-' || c == '+' || c == ':' || c == ',' || c == '=' || c == '%' || c == '@';
  });
  if (plain) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

void check_partition(const std::string& partition) {
  static const std::regex re(R"([A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*)");
  if (!std::regex_match(partition, re))
    throw Error(ErrorInfo{.path = "--partition", .expected = "partition names (letters, digits, _ . -), comma-separated", .found = "'" + partition + "'"});
}

void check_time_limit(const std::string& time) {
  // Slurm's forms: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S; or no limit.
  static const std::regex re(R"(\d{1,7}(:\d{1,2}){0,2}|\d{1,5}-\d{1,2}(:\d{1,2}){0,2}|UNLIMITED|INFINITE)");
  if (!std::regex_match(time, re))
    throw Error(ErrorInfo{.path = "--time", .expected = "a Slurm time limit: MINUTES, H:M:S, D-H or D-H:M:S, e.g. 2:00:00", .found = "'" + time + "'"});
}

std::string render_script(const SlurmFarm& farm) {
  return header("# Renders the frames of one Welkin sequence: each array task renders one shard of them.\n") +
         "#SBATCH --job-name=welkin-render\n"
         "#SBATCH --array=0-" + std::to_string(farm.tasks - 1) + "\n"
         "#SBATCH --output=" + kSlurmFolder + "/render-%A_%a.log\n" +
         resources(farm) + sequence_command(farm) + " \\\n"
         "  --shard \"$SLURM_ARRAY_TASK_ID/" + std::to_string(farm.tasks) + "\" --resume\n"
         "# --resume: a task run again (requeued, resubmitted) renders only the frames still missing.\n";
}

std::string assemble_script(const SlurmFarm& farm) {
  std::string outputs;
  if (!farm.contact_sheet.empty()) outputs += " \\\n  --contact-sheet " + shell_quote(farm.contact_sheet);
  if (!farm.video.empty()) outputs += " \\\n  --video " + shell_quote(farm.video);
  return header("# Assembles the frames the render job wrote: checks every frame is there (renders any that is\n"
                "# not), then writes the contact sheet and the video, where asked for.\n") +
         "#SBATCH --job-name=welkin-assemble\n"
         "#SBATCH --output=" + kSlurmFolder + "/assemble-%j.log\n"
         "#SBATCH --kill-on-invalid-dep=yes\n" +
         resources(farm) + sequence_command(farm) + " \\\n  --resume" + outputs + "\n";
}

std::vector<std::string> sbatch_arguments(const SlurmFarm& farm, const std::string& script, const std::string& after_job) {
  // --chdir: the job runs in the frames folder, so the scripts' relative log names land there.
  std::vector<std::string> args{"sbatch", "--parsable", "--chdir=" + farm.out_dir};
  if (!after_job.empty()) args.push_back("--dependency=afterok:" + after_job);
  args.push_back((std::filesystem::path(farm.out_dir) / kSlurmFolder / script).string());
  return args;
}

std::string parse_job_id(const std::string& sbatch_output) {
  static const std::regex re(R"(\s*(\d{1,18})(;\S*)?\s*)");
  std::smatch m;
  return std::regex_match(sbatch_output, m, re) ? m[1].str() : std::string();
}

}  // namespace welkin::cli
