// The disk cache gives back exactly what was stored under exactly the key asked for, and reads
// anything else (another key in the same file, a truncated or damaged file, a FIFO) as a miss.
#include "welkin/core/disk_cache.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  fs::path d = welkin::testing::scratch_folder("welkin-disk-cache-test") / name;
  fs::remove_all(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string as_string(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }

TEST(DiskCache, GivesBackWhatWasStoredUnderTheSameKey) {
  const welkin::DiskCache cache(fresh_dir("roundtrip").string());
  const std::string key("a key\0with a zero byte", 22), payload("\x00\x01\x02 payload \xff", 13);
  EXPECT_FALSE(cache.read(key, payload.size()));  // the folder does not exist yet
  ASSERT_TRUE(cache.write(key, payload));
  const auto back = cache.read(key, payload.size());
  ASSERT_TRUE(back);
  EXPECT_EQ(as_string(*back), payload);
  // The size asked for is part of what must match, and so is every byte of the key.
  EXPECT_FALSE(cache.read(key, payload.size() + 1));
  EXPECT_FALSE(cache.read(std::string(key).replace(21, 1, "X"), payload.size()));
  // Stored again, the new bytes replace the old ones.
  ASSERT_TRUE(cache.write(key, "other bytes!!"));
  EXPECT_EQ(as_string(*cache.read(key, 13)), "other bytes!!");
}

TEST(DiskCache, AnotherKeyInTheSameFileIsAMiss) {
  // A file holding another key under this key's name, as a hash collision would leave it.
  const welkin::DiskCache cache(fresh_dir("collision").string());
  ASSERT_TRUE(cache.write("first", "0123456789"));
  fs::rename(cache.path_of("first"), cache.path_of("second"));
  EXPECT_FALSE(cache.read("second", 10));
  EXPECT_FALSE(cache.read("first", 10));
}

TEST(DiskCache, DamagedFilesAreMisses) {
  const welkin::DiskCache cache(fresh_dir("damaged").string());
  const std::string payload(1000, 'p');
  ASSERT_TRUE(cache.write("k", payload));
  const fs::path file = cache.path_of("k");
  const std::string good = slurp(file);
  // A flipped payload byte fails the checksum; a truncated or a lengthened file fails the size.
  std::string flipped = good;
  flipped[flipped.size() / 2] ^= 0x20;
  std::ofstream(file, std::ios::binary) << flipped;
  EXPECT_FALSE(cache.read("k", payload.size()));
  std::ofstream(file, std::ios::binary) << good.substr(0, good.size() - 1);
  EXPECT_FALSE(cache.read("k", payload.size()));
  std::ofstream(file, std::ios::binary) << good + "x";
  EXPECT_FALSE(cache.read("k", payload.size()));
  // A FIFO where the file should be is refused at once, not read (it would block).
  fs::remove(file);
  ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
  EXPECT_FALSE(cache.read("k", payload.size()));
  fs::remove(file);
  std::ofstream(file, std::ios::binary) << good;
  EXPECT_EQ(as_string(*cache.read("k", payload.size())), payload);
}

TEST(DiskCache, PayloadChecksumIsCrc32) {
  // The file ends with the payload's CRC-32 (8 bytes, little-endian): "123456789" has the published
  // check value 0xCBF43926.
  const welkin::DiskCache cache(fresh_dir("crc").string());
  ASSERT_TRUE(cache.write("k", "123456789"));
  const std::string file = slurp(cache.path_of("k"));
  ASSERT_GE(file.size(), 8u);
  uint64_t stored = 0;
  for (int i = 0; i < 8; ++i) stored |= uint64_t(uint8_t(file[file.size() - 8 + size_t(i)])) << (8 * i);
  EXPECT_EQ(stored, 0xCBF43926ull);
}

TEST(DiskCache, DisabledOrUnwritableStoresNothing) {
  const welkin::DiskCache off;
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.write("k", "v"));
  EXPECT_FALSE(off.read("k", 1));
  // A file where the folder should be: the write fails, with a warning, not an error.
  const fs::path blocked = fresh_dir("blocked");
  fs::create_directories(blocked.parent_path());
  std::ofstream(blocked) << "a file";
  const welkin::DiskCache cache((blocked / "cache").string());
  EXPECT_FALSE(cache.write("k", "v"));
  EXPECT_FALSE(cache.read("k", 1));
}

TEST(DiskCache, FolderFromTheEnvironment) {
  std::map<std::string, std::optional<std::string>> saved;
  for (const char* name : {"WELKIN_CACHE_DIR", "XDG_CACHE_HOME", "HOME"})
    if (const char* v = std::getenv(name)) saved[name] = v; else saved[name] = std::nullopt;
  ::setenv("WELKIN_CACHE_DIR", "/some/where", 1);
  EXPECT_EQ(welkin::DiskCache::from_environment().folder(), "/some/where");
  ::setenv("WELKIN_CACHE_DIR", "", 1);  // set and empty: no cache
  EXPECT_FALSE(welkin::DiskCache::from_environment().enabled());
  ::unsetenv("WELKIN_CACHE_DIR");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(welkin::DiskCache::from_environment().folder(), "/xdg/welkin");
  ::unsetenv("XDG_CACHE_HOME");
  ::setenv("HOME", "/home/someone", 1);
  EXPECT_EQ(welkin::DiskCache::from_environment().folder(), "/home/someone/.cache/welkin");
  for (const auto& [name, value] : saved)
    if (value) ::setenv(name.c_str(), value->c_str(), 1); else ::unsetenv(name.c_str());
}

TEST(DiskCache, HashIsFnv1a) {
  // Published FNV-1a 64 test vectors.
  EXPECT_EQ(welkin::DiskCache::hash(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(welkin::DiskCache::hash("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(welkin::DiskCache::hash("foobar"), 0x85944171f73967e8ull);
}

}  // namespace
