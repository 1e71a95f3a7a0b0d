#include "welkin/core/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "welkin/core/error.h"

namespace welkin {

namespace fs = std::filesystem;

namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes a descriptor on every path out of a function (errors of this close are not interesting:
// the checked close of a written file is done explicitly).
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

template <class Bytes>
Bytes read_whole(const std::string& path, uint64_t max_bytes) {
  auto fail = [&](const std::string& message) -> Error {
    return Error(ErrorInfo{.file = path, .message = message});
  };
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
  if (f.fd < 0) throw fail(std::string("cannot open file: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw fail(std::string("cannot read file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw fail("cannot read " + kind_of(st.st_mode) + "; expected a regular file");
  if (uint64_t(st.st_size) > max_bytes)
    throw fail("file is " + std::to_string(st.st_size) + " bytes; the limit is " + std::to_string(max_bytes));
  Bytes out;
  out.resize(size_t(st.st_size));
  size_t got = 0;
  for (;;) {
    if (got == out.size()) {
      // The file may have grown since fstat (or /proc reports size 0): read on, never past the limit.
      if (uint64_t(out.size()) >= max_bytes) {
        char probe;
        const ssize_t n = ::read(f.fd, &probe, 1);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw fail(std::string("cannot read file: ") + std::strerror(errno));
        if (n > 0) throw fail("file is larger than the limit of " + std::to_string(max_bytes) + " bytes");
        break;
      }
      out.resize(size_t(std::min<uint64_t>(max_bytes, uint64_t(out.size()) + 65536)));
    }
    const ssize_t n = ::read(f.fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw fail(std::string("cannot read file: ") + std::strerror(errno));
    if (n == 0) break;
    got += size_t(n);
  }
  out.resize(got);
  return out;
}

// The file a write to `path` must replace: symbolic links are followed so the link survives.
fs::path resolve_links(const std::string& path) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::error_code ec;
    fs::path target = fs::read_symlink(p, ec);
    if (ec) throw Error(ErrorInfo{.file = path, .message = "cannot follow symbolic link: " + ec.message()});
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  throw Error(ErrorInfo{.file = path, .message = "too many levels of symbolic links"});
}

// A name no other writer (this process's other threads included) picks: pid, counter and clock.
std::string temp_name(const fs::path& target) {
  static std::atomic<uint64_t> counter{0};
  const uint64_t tick = uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
  return "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
         std::to_string(counter++) + "-" + std::to_string(tick % 1000003);
}

bool write_all(int fd, std::string_view bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, std::min<size_t>(bytes.size() - done, size_t(1) << 30));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace

std::string read_file_text(const std::string& path, uint64_t max_bytes) {
  return read_whole<std::string>(path, max_bytes);
}

std::vector<uint8_t> read_file_bytes(const std::string& path, uint64_t max_bytes) {
  return read_whole<std::vector<uint8_t>>(path, max_bytes);
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  const fs::path target = resolve_links(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  auto fail = [&](const std::string& what, int err, bool existed) -> Error {
    return Error(ErrorInfo{.file = path,
                           .message = "cannot write: " + what +
                                      (err ? std::string(": ") + std::strerror(err) : "") +
                                      (existed ? " (the existing file was kept)" : "")});
  };

  struct stat old {};
  const bool existed = ::stat(target.c_str(), &old) == 0;
  if (existed && !S_ISREG(old.st_mode)) throw fail("the target is " + kind_of(old.st_mode), 0, true);

  // O_EXCL: never write into a file someone else created (or a link planted) under the temporary name.
  fs::path tmp;
  Fd f;
  for (int attempt = 0; attempt < 100 && f.fd < 0; ++attempt) {
    tmp = dir / temp_name(target);
    f.fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (f.fd < 0 && errno != EEXIST)
      throw fail("cannot create a temporary file in " + dir.string(), errno, existed);
  }
  if (f.fd < 0) throw fail("cannot create a temporary file in " + dir.string(), EEXIST, existed);

  auto abandon = [&](const std::string& what, int err) -> Error {
    if (f.fd >= 0) ::close(f.fd), f.fd = -1;
    ::unlink(tmp.c_str());
    return fail(what, err, existed);
  };
  // Keep the old file's permissions (0666 minus the umask for a new file, as open gave it).
  if (existed && ::fchmod(f.fd, old.st_mode & 07777) != 0) throw abandon("cannot keep the file mode", errno);
  if (!write_all(f.fd, bytes)) throw abandon("write failed", errno);
  if (::fsync(f.fd) != 0) throw abandon("cannot flush to disk", errno);
  const int fd = f.fd;
  f.fd = -1;
  if (::close(fd) != 0) throw abandon("close failed", errno);
  if (::rename(tmp.c_str(), target.c_str()) != 0) throw abandon("cannot replace the file", errno);
  // The rename itself is durable only once the folder is synced.
  Fd d{::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (d.fd < 0 || (::fsync(d.fd) != 0 && errno != EINVAL))
    throw fail("written, but the folder " + dir.string() + " could not be synced", errno, false);
}

}  // namespace welkin
