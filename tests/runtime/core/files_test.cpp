// The one reader and the one writer every file goes through: regular files only, bounded reads,
// atomic writes that keep the old file, its mode and symbolic links.
#include "welkin/core/files.h"

#include <gtest/gtest.h>

#include "error_of.h"
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "welkin/core/error.h"
#include "welkin/gfx/image.h"
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  fs::path d = welkin::testing::scratch_folder("welkin-files-test") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// Nothing but the named files is left in `dir` (no temporary files after success or failure).
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

using welkin::testing::error_of;

TEST(AtomicWrite, CreatesAndReplacesLeavingNoTemporaryFile) {
  fs::path d = fresh_dir("replace");
  welkin::write_file_atomically((d / "a.txt").string(), "first");
  welkin::write_file_atomically((d / "a.txt").string(), std::string("sec\0nd", 6));
  EXPECT_EQ(slurp(d / "a.txt"), std::string("sec\0nd", 6));
  EXPECT_EQ(entries(d), std::vector<std::string>{"a.txt"});
}

TEST(AtomicWrite, KeepsTheModeOfTheFileItReplaces) {
  fs::path d = fresh_dir("mode");
  put(d / "secret.json", "old");
  ASSERT_EQ(::chmod((d / "secret.json").c_str(), 0640), 0);
  welkin::write_file_atomically((d / "secret.json").string(), "new");
  struct stat st {};
  ASSERT_EQ(::stat((d / "secret.json").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_EQ(slurp(d / "secret.json"), "new");
}

TEST(AtomicWrite, WritingThroughASymlinkUpdatesItsTarget) {
  fs::path d = fresh_dir("symlink");
  fs::create_directories(d / "real");
  put(d / "real" / "scene.json", "old");
  fs::create_symlink("real/scene.json", d / "link.json");
  welkin::write_file_atomically((d / "link.json").string(), "new");
  EXPECT_TRUE(fs::is_symlink(d / "link.json")) << "the link was replaced by a file";
  EXPECT_EQ(slurp(d / "real" / "scene.json"), "new");
  EXPECT_EQ(entries(d / "real"), std::vector<std::string>{"scene.json"});
}

TEST(AtomicWrite, RefusesToReplaceAFolderOrAFifo) {
  fs::path d = fresh_dir("nonregular");
  fs::create_directories(d / "out.png");
  put(d / "out.png" / "inside", "keep");
  std::string e = error_of([&] { welkin::write_file_atomically((d / "out.png").string(), "x"); });
  EXPECT_NE(e.find((d / "out.png").string()), std::string::npos) << e;
  EXPECT_NE(e.find("folder"), std::string::npos) << e;
  EXPECT_EQ(slurp(d / "out.png" / "inside"), "keep");
  ASSERT_EQ(::mkfifo((d / "pipe").c_str(), 0644), 0);
  e = error_of([&] { welkin::write_file_atomically((d / "pipe").string(), "x"); });
  EXPECT_NE(e.find("FIFO"), std::string::npos) << e;
  struct stat st {};
  ASSERT_EQ(::lstat((d / "pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(entries(d), (std::vector<std::string>{"out.png", "pipe"}));
}

TEST(AtomicWrite, MissingOrReadOnlyFolderGivesOneErrorNamingTheFile) {
  fs::path d = fresh_dir("readonly");
  const std::string missing = (d / "nope" / "x.csv").string();
  std::string e = error_of([&] { welkin::write_file_atomically(missing, "x"); });
  EXPECT_EQ(e.rfind(missing, 0), 0u) << e;
  if (::geteuid() != 0) {  // root writes into read-only folders
    put(d / "x.csv", "old");
    ::chmod(d.c_str(), 0555);
    e = error_of([&] { welkin::write_file_atomically((d / "x.csv").string(), "new"); });
    ::chmod(d.c_str(), 0755);
    EXPECT_NE(e.find("existing file was kept"), std::string::npos) << e;
    EXPECT_EQ(slurp(d / "x.csv"), "old");
  }
}

// A full disk, simulated with a file size limit (works for root too): the write fails part way, the
// old file survives whole and the temporary file is removed. Run in a child process (death test)
// so the limit does not outlive the test.
void write_under_size_limit(const std::function<void()>& write) {
  std::signal(SIGXFSZ, SIG_IGN);  // make write() fail with EFBIG instead of killing the process
  rlimit limit{.rlim_cur = 4096, .rlim_max = RLIM_INFINITY};
  ::setrlimit(RLIMIT_FSIZE, &limit);
  try {
    write();
  } catch (const welkin::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::_Exit(3);
  }
  std::_Exit(0);
}

TEST(AtomicWriteDeathTest, FullDiskKeepsTheOldFile) {
  fs::path d = fresh_dir("full");
  const std::string file = (d / "scene.json").string();
  put(file, "the good old content");
  EXPECT_EXIT(write_under_size_limit([&] { welkin::write_file_atomically(file, std::string(100000, 'x')); }),
              ::testing::ExitedWithCode(3), "scene.json: cannot write: write failed.*existing file was kept");
  EXPECT_EQ(slurp(file), "the good old content");
  EXPECT_EQ(entries(d), std::vector<std::string>{"scene.json"});
}

TEST(AtomicWriteDeathTest, FullDiskKeepsTheOldImage) {
  fs::path d = fresh_dir("full-png");
  const std::string png = (d / "frame.png").string();
  welkin::ImageU8 small{2, 2, std::vector<uint8_t>(16, 200)};
  welkin::write_png(png, small);
  const std::string before = slurp(png);
  welkin::ImageU8 big{256, 256, {}};
  big.rgba.resize(256 * 256 * 4);
  uint32_t x = 2463534242u;  // xorshift noise: incompressible, so the PNG is far over the size limit
  for (uint8_t& v : big.rgba) x ^= x << 13, x ^= x >> 17, x ^= x << 5, v = uint8_t(x);
  EXPECT_EXIT(write_under_size_limit([&] { welkin::write_png(png, big); }), ::testing::ExitedWithCode(3),
              "frame.png: cannot write");
  EXPECT_TRUE(slurp(png) == before) << "the old image was replaced";
  EXPECT_EQ(welkin::read_png(png).width, 2);
  EXPECT_EQ(entries(d), std::vector<std::string>{"frame.png"});
}

TEST(BoundedRead, RefusesFifosDevicesAndFoldersWithoutBlocking) {
  ::alarm(20);  // a reader that blocks on the FIFO fails the test instead of hanging it
  fs::path d = fresh_dir("read");
  ASSERT_EQ(::mkfifo((d / "scene.json").c_str(), 0644), 0);
  std::string e = error_of([&] { welkin::read_file_text((d / "scene.json").string()); });
  EXPECT_NE(e.find("FIFO"), std::string::npos) << e;
  EXPECT_EQ(e.rfind((d / "scene.json").string(), 0), 0u) << e;
  e = error_of([&] { welkin::read_file_bytes("/dev/zero"); });
  EXPECT_NE(e.find("/dev/zero: cannot read a device"), std::string::npos) << e;
  e = error_of([&] { welkin::read_file_text(d.string()); });
  EXPECT_NE(e.find("folder"), std::string::npos) << e;
  e = error_of([&] { welkin::read_file_text((d / "missing").string()); });
  EXPECT_NE(e.find("cannot open file"), std::string::npos) << e;
  ::alarm(0);
}

TEST(BoundedRead, StopsAtTheLimit) {
  fs::path d = fresh_dir("limit");
  put(d / "f", std::string(1000, 'a'));
  EXPECT_EQ(welkin::read_file_text((d / "f").string(), 1000).size(), 1000u);
  std::string e = error_of([&] { welkin::read_file_text((d / "f").string(), 999); });
  EXPECT_NE(e.find("1000 bytes; the limit is 999"), std::string::npos) << e;
  // Files whose size stat does not know (/proc) are read to their end, still bounded.
  EXPECT_FALSE(welkin::read_file_text("/proc/self/status", 1 << 20).empty());
  e = error_of([&] { welkin::read_file_text("/proc/self/status", 10); });
  EXPECT_NE(e.find("larger than the limit of 10 bytes"), std::string::npos) << e;
}

TEST(BoundedRead, ImagesOverTheSizeBoundAreRefusedFromTheHeader) {
  fs::path d = fresh_dir("image");
  welkin::ImageU8 wide{welkin::kMaxImageSide + 1, 1, std::vector<uint8_t>(size_t(welkin::kMaxImageSide + 1) * 4, 0)};
  welkin::write_png((d / "wide.png").string(), wide);
  std::string e = error_of([&] { welkin::read_png((d / "wide.png").string()); });
  EXPECT_NE(e.find("16385x1"), std::string::npos) << e;
  welkin::ImageF wide_hdr{welkin::kMaxImageSide + 1, 1, std::vector<float>(size_t(welkin::kMaxImageSide + 1) * 4, 0.5f)};
  welkin::write_exr((d / "wide.exr").string(), wide_hdr);
  e = error_of([&] { welkin::read_exr((d / "wide.exr").string()); });
  EXPECT_EQ(e.rfind((d / "wide.exr").string() + ": ", 0), 0u) << e;
  EXPECT_NE(e.find("16384"), std::string::npos) << e;  // the bound, in our words or OpenEXR's
  ASSERT_EQ(::mkfifo((d / "pipe.exr").c_str(), 0644), 0);
  e = error_of([&] { welkin::read_exr((d / "pipe.exr").string()); });
  EXPECT_NE(e.find("FIFO"), std::string::npos) << e;
}

}  // namespace
