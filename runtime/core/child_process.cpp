#include "welkin/core/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/common_interface_defs.h>
#define WELKIN_CHILD_UNDER_ASAN 1
#endif
#endif

namespace welkin {

namespace {

// What the child writes before the work's bytes: how the work ended and how many bytes follow.
enum : uint8_t { kReturned = 0, kOutOfMemory = 1, kThrew = 2 };
constexpr size_t kHeaderBytes = 1 + sizeof(uint64_t);

bool write_all(int fd, const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= size_t(n);
  }
  return true;
}

// The child's address space now (it starts as a copy of the caller's, which may be large).
uint64_t address_space_bytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  unsigned long long pages = 0;
  if (f) {
    if (std::fscanf(f, "%llu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return uint64_t(pages) * uint64_t(sysconf(_SC_PAGESIZE));
}

// RLIMIT_CPU counts whole seconds.
long long cpu_seconds(const ChildLimits& limits) {
  return std::max(1LL, (long long)std::ceil(limits.seconds));
}

[[noreturn]] void child_main(int fd, const std::function<std::vector<uint8_t>()>& work,
                             const ChildLimits& limits) {
  // The caller's handlers (the editor saves its work on a crash) are not the child's to run.
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTERM, SIGINT, SIGHUP, SIGXCPU, SIGPIPE})
    signal(s, SIG_DFL);
  const rlim_t cpu = rlim_t(cpu_seconds(limits));
  const rlimit cpu_limit{cpu, cpu + 1};
  const rlim_t memory = rlim_t(address_space_bytes() + limits.memory_bytes);
  const rlimit memory_limit{memory, memory};
  const rlimit no_core{0, 0};
  if (setrlimit(RLIMIT_CPU, &cpu_limit) != 0 || setrlimit(RLIMIT_AS, &memory_limit) != 0 ||
      setrlimit(RLIMIT_CORE, &no_core) != 0)
    _exit(3);
#ifdef WELKIN_CHILD_UNDER_ASAN
  // ASan dies on a failed `new` instead of throwing; libFuzzer's death callback would then record
  // the child's limit as a finding of the fuzzer's own process.
  __sanitizer_set_death_callback(nullptr);
#endif
  uint8_t how = kReturned;
  std::vector<uint8_t> bytes;
  try {
    bytes = work();
  } catch (const std::bad_alloc&) {
    how = kOutOfMemory, bytes.clear();
  } catch (...) {
    how = kThrew, bytes.clear();
  }
  const uint64_t size = bytes.size();
  const bool ok = write_all(fd, &how, 1) && write_all(fd, &size, sizeof size) &&
                  write_all(fd, bytes.data(), bytes.size());
  _exit(ok ? 0 : 4);
}

}  // namespace

ChildResult run_in_child(const std::function<std::vector<uint8_t>()>& work, const ChildLimits& limits) {
  ChildResult result;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    result.status = ChildResult::Status::unavailable,
    result.detail = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    result.status = ChildResult::Status::unavailable,
    result.detail = std::string("fork: ") + std::strerror(errno);
    close(fds[0]), close(fds[1]);
    return result;
  }
  if (pid == 0) {
    close(fds[0]);
    child_main(fds[1], work, limits);
  }
  close(fds[1]);
  using clock = std::chrono::steady_clock;
  const double wall = limits.wall_seconds > 0.0 ? limits.wall_seconds : 4.0 * limits.seconds + 1.0;
  const auto deadline = clock::now() + std::chrono::duration<double>(wall);
  std::vector<uint8_t> received;
  bool killed_at_time = false, too_large = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    if (left <= 0) {
      killed_at_time = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int r = poll(&p, 1, int(std::min<long long>(left, 1000)));
    if (r < 0 && errno != EINTR) break;
    if (r <= 0) continue;
    uint8_t chunk[65536];
    const ssize_t n = read(fds[0], chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child has finished or died
    if (received.size() + size_t(n) > limits.max_result_bytes + kHeaderBytes) {
      too_large = true;
      break;
    }
    received.insert(received.end(), chunk, chunk + n);
  }
  close(fds[0]);
  if (killed_at_time || too_large) kill(pid, SIGKILL);
  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }
  if (killed_at_time) {
    result.status = ChildResult::Status::over_time, result.detail = "wall-clock limit";
    return result;
  }
  if (too_large) {
    result.status = ChildResult::Status::over_result;
    return result;
  }
  if (WIFSIGNALED(wait_status)) {
    const int s = WTERMSIG(wait_status);
    result.status =
        s == SIGXCPU || s == SIGKILL ? ChildResult::Status::over_time : ChildResult::Status::failed;
    result.detail = "signal " + std::to_string(s) + " (" + strsignal(s) + ")";
    return result;
  }
  uint64_t size = 0;
  if (received.size() >= kHeaderBytes) std::memcpy(&size, received.data() + 1, sizeof size);
  if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0 || received.size() < kHeaderBytes ||
      size != received.size() - kHeaderBytes) {
    result.detail = "exit without a complete result";
    return result;
  }
  switch (received[0]) {
    case kReturned:
      result.status = ChildResult::Status::ok;
      result.bytes.assign(received.begin() + kHeaderBytes, received.end());
      break;
    case kOutOfMemory:
      result.status = ChildResult::Status::over_memory;
      break;
    default:
      result.detail = "an exception";
      break;
  }
  return result;
}

std::string describe(const ChildResult& result, const ChildLimits& limits) {
  const std::string seconds = std::to_string(cpu_seconds(limits));
  switch (result.status) {
    case ChildResult::Status::ok: return "finished";
    case ChildResult::Status::over_time: return std::string("more than ") + seconds + " s of CPU time";
    case ChildResult::Status::over_memory:
      return "more than " + std::to_string(limits.memory_bytes >> 20) + " MiB of memory";
    case ChildResult::Status::over_result:
      return "a result over " + std::to_string(limits.max_result_bytes) + " bytes";
    case ChildResult::Status::failed: return "a crash (" + result.detail + ")";
    case ChildResult::Status::unavailable: return "no child process (" + result.detail + ")";
  }
  return result.detail;
}

}  // namespace welkin
