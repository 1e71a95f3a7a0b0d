#include "program.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

namespace welkin::cli {

extern "C" char** environ;

namespace {

// The pipe's ends, closed on every way out.
struct Pipe {
  int fd[2] = {-1, -1};
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
};

}  // namespace

ProgramResult run_program(const std::vector<std::string>& args, bool capture_output) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Pipe out;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (capture_output) {
    if (::pipe2(out.fd, O_CLOEXEC) != 0) return {};
    posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);  // dup2 clears CLOEXEC
  }
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return {};
  ProgramResult result;
  if (capture_output) {
    ::close(out.fd[1]);
    out.fd[1] = -1;
    char buf[4096];
    for (;;) {
      const ssize_t n = ::read(out.fd[0], buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      result.output.append(buf, size_t(n));
    }
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return {};
  }
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

}  // namespace welkin::cli
