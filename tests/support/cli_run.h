#pragma once
// Running the `welkin` program from a test as a user would: exit code, output, crash detection.
// WELKIN_EXE is defined by the test target.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "scratch_folder.h"

namespace welkin::testing {

struct CliRun {
  int code = -1;
  std::string out;  // stdout, and stderr unless dropped
  bool signaled = false;
};

inline CliRun run_welkin(const std::string& args, bool with_stderr = true) {
  std::string cmd = std::string(WELKIN_EXE) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
  int status = pclose(p);
  r.signaled = WIFSIGNALED(status);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}


}  // namespace welkin::testing
