#pragma once
// Starting other programs (ffmpeg, sbatch) with an argument vector, never through a shell, so file
// names reach them literally.
#include <string>
#include <vector>

namespace welkin::cli {

struct ProgramResult {
  int status = -1;     // exit status; 128 + signal where it was killed; -1 where it could not be started
  std::string output;  // its standard output, where asked for (standard error passes through)
};

// Runs a program found on PATH (args[0]) and waits for it.
ProgramResult run_program(const std::vector<std::string>& args, bool capture_output = false);

}  // namespace welkin::cli
