#pragma once
// The Slurm batch scripts of `welkin farm slurm`: a job array whose tasks each render one shard of a
// run's frames, and an assembling job after it (checks every frame, writes the contact sheet and the
// video). Plain bash a cluster user can read and edit; every file name in them is single-quoted, so no
// name is ever read as shell code.
#include <string>
#include <vector>

#include "run_folder.h"

namespace welkin::cli {

struct SlurmFarm {
  RunManifest run;                   // scene and sequence as absolute paths
  std::string welkin;                // absolute path of the welkin the tasks run
  std::string out_dir;               // absolute
  int tasks = 1;                     // array tasks, one shard each
  std::string partition, time;       // #SBATCH --partition and --time where set (checked)
  std::string contact_sheet, video;  // absolute, where asked for
};

// The folder inside the frames folder that holds the scripts, Slurm's logs and the job ids.
inline constexpr const char* kSlurmFolder = "slurm";

// `text` as one shell word: unchanged where it holds only characters no shell treats specially,
// else in single quotes with each embedded ' written as '\''.
std::string shell_quote(const std::string& text);
// Throw Error naming --partition / --time for values sbatch would not take (or that would break a line).
void check_partition(const std::string& partition);
void check_time_limit(const std::string& time);

std::string render_script(const SlurmFarm& farm);
std::string assemble_script(const SlurmFarm& farm);
// sbatch's arguments for a script in the farm's folder; `after_job` (may be empty) is the job it waits for.
std::vector<std::string> sbatch_arguments(const SlurmFarm& farm, const std::string& script, const std::string& after_job);
// The job id in `sbatch --parsable`'s output ("123" or "123;cluster"), or "" where there is none.
std::string parse_job_id(const std::string& sbatch_output);

}  // namespace welkin::cli
