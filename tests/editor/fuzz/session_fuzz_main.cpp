// welkin_editor_session_fuzz: random editor sessions with the editor's promises checked after every
// line (session_fuzz.h).
//   welkin_editor_session_fuzz [--seed N] [--sessions N | --seconds S] [--steps N] [--out DIR]
//   welkin_editor_session_fuzz --replay FILE...   (sessions kept as scripts: each must hold)
// A failing session is shrunk and written to DIR (default: the working folder) as a script to
// commit under tests/editor/sessions/fuzz/. Exit status 1 on any failure.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "session_fuzz.h"
#include "scratch_folder.h"

namespace {

using namespace welkin::editor::fuzz;
namespace fs = std::filesystem;

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", path.c_str());
    std::exit(2);
  }
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

int replay(const FuzzFolder& folder, const std::vector<std::string>& files) {
  int failed = 0;
  for (const std::string& f : files) {
    std::vector<std::string> lines = read_lines(f);
    if (std::optional<Failure> failure = run_session(folder, lines)) {
      std::fprintf(stderr, "%s:%zu: %s\n  (line: %s)\n", f.c_str(), failure->line + 1, failure->what.c_str(),
                   lines[failure->line].c_str());
      ++failed;
    } else {
      std::printf("%s: %zu lines, every invariant held\n", f.c_str(), lines.size());
    }
  }
  return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t seed = 1;
  size_t sessions = 0, steps = 60;
  double seconds = 0;
  std::string out = ".";
  std::vector<std::string> replays;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&] {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::string(argv[++i]);
    };
    if (a == "--seed")
      seed = std::stoull(value());
    else if (a == "--sessions")
      sessions = std::stoull(value());
    else if (a == "--seconds")
      seconds = std::stod(value());
    else if (a == "--steps")
      steps = std::stoull(value());
    else if (a == "--out")
      out = value();
    else if (a == "--replay")
      while (i + 1 < argc) replays.push_back(argv[++i]);
    else {
      std::fprintf(
          stderr,
          "usage: %s [--seed N] [--sessions N | --seconds S] [--steps N] [--out DIR] | --replay FILE...\n",
          argv[0]);
      return 2;
    }
  }
  const FuzzFolder folder(welkin::testing::scratch_folder("welkin-session-fuzz") / "folder");
  int status = 0;
  if (!replays.empty()) {
    status = replay(folder, replays);
  } else {
    if (!sessions && !seconds) sessions = 100;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    size_t run = 0, lines = 0;
    for (; sessions ? run < sessions : elapsed() < seconds; ++run) {
      std::optional<Failure> failure;
      std::vector<std::string> session = random_session(folder, seed + run, steps, failure);
      lines += session.size();
      if (!failure) continue;
      std::fprintf(stderr, "seed %llu, line %zu: %s\n", (unsigned long long)(seed + run), failure->line + 1,
                   failure->what.c_str());
      std::vector<std::string> shrunk = shrink(folder, session, *failure);
      const std::optional<Failure> again = run_session(folder, shrunk);
      const fs::path file = fs::path(out) / ("session-fuzz-seed-" + std::to_string(seed + run) + ".script");
      std::string what = again ? again->what : failure->what;
      for (char& c : what)
        if (c == '\n') c = ' ';  // one comment line
      std::ofstream script(file);
      script << "# Found by welkin_editor_session_fuzz (seed " << seed + run << "): " << what << "\n";
      for (const std::string& l : shrunk) script << l << "\n";
      std::fprintf(stderr, "shrunk from %zu to %zu lines: %s\n", session.size(), shrunk.size(), file.c_str());
      status = 1;
      break;
    }
    std::printf("%zu sessions, %zu lines in %.1f s (seeds %llu to %llu): %s\n", run + (status ? 1 : 0), lines,
                elapsed(), (unsigned long long)seed, (unsigned long long)(seed + run - (status ? 0 : 1)),
                status ? "a failure, see above" : "every invariant held");
  }
  fs::remove_all(folder.root());
  return status;
}
