#pragma once
// Work that cannot be bounded from outside (a third-party decoder trusting counts deep inside its
// input) runs in a forked child process under a CPU-time, wall-time and memory limit; its result
// comes back as bytes through a pipe. A limit that is hit kills the child, never the caller.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace welkin {

struct ChildLimits {
  double seconds = 2.0;       // CPU time, rounded up to whole seconds (RLIMIT_CPU)
  // a child that blocks is killed after this (0: 4 x seconds + 1, room for a loaded machine)
  double wall_seconds = 0.0;
  uint64_t memory_bytes = 256 << 20;  // address space the child may add to what it inherits
  uint64_t max_result_bytes = 1 << 20;
};

struct ChildResult {
  enum class Status {
    ok,             // `bytes` holds what the work returned
    over_time,      // killed at the time limit
    over_memory,    // an allocation failed at the memory limit
    over_result,    // it returned more than max_result_bytes
    failed,         // it died another way (a signal, an exit without a result)
    unavailable,    // no child could be started (fork or pipe failed)
  };
  Status status = Status::failed;
  std::vector<uint8_t> bytes;
  std::string detail;  // what happened, for an error message ("signal 11", "fork: ...")
};

// Runs `work` in a child process under `limits`. In the child, a std::bad_alloc from `work` reads as
// over_memory; any other exception as failed. Signal handlers the caller installed are reset in the
// child, which leaves with _exit (no destructors or atexit handlers of the caller's state run twice).
ChildResult run_in_child(const std::function<std::vector<uint8_t>()>& work, const ChildLimits& limits);

// One line naming the limit that was hit, e.g. "more than 2 s of CPU time".
std::string describe(const ChildResult& result, const ChildLimits& limits);

}  // namespace welkin
