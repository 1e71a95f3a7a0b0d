#include "welkin/core/disk_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <zlib.h>

#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/core/log.h"

namespace welkin {

namespace {

// '2': the payload's checksum is CRC-32 (version 1 had FNV-1a, which reads a byte per multiply: a tenth
// of the default demo's start went into checking its 77 MB of cached entries).
constexpr char kMagic[8] = {'W', 'E', 'L', 'K', 'I', 'N', 'C', '2'};
// Keys are descriptions (parameters, shader sources); a larger one is a mistake, not a key.
constexpr size_t kMaxKeyBytes = 16u << 20;

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}
uint64_t get_u64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}

// zlib's CRC-32 of the payload: detects any burst of damage up to 32 bits and other damage but for one
// chance in 2^32 (sizes and keys are compared exactly besides).
uint64_t checksum(std::string_view bytes) {
  return crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(bytes.data()), bytes.size());
}

}  // namespace

uint64_t DiskCache::hash(std::string_view bytes, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

DiskCache DiskCache::from_environment() {
  if (const char* dir = std::getenv("WELKIN_CACHE_DIR")) return DiskCache(dir);
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return DiskCache((std::filesystem::path(xdg) / "welkin").string());
  if (const char* home = std::getenv("HOME"); home && *home)
    return DiskCache((std::filesystem::path(home) / ".cache" / "welkin").string());
  return DiskCache();
}

DiskCache::DiskCache(std::string folder) : folder_(std::move(folder)) {}

std::string DiskCache::path_of(std::string_view key) const {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", (unsigned long long)hash(key));
  return (std::filesystem::path(folder_) / name).string();
}

std::optional<std::vector<uint8_t>> DiskCache::read(std::string_view key, size_t size) const {
  if (!enabled() || key.size() > kMaxKeyBytes) return std::nullopt;
  const std::string path = path_of(key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  const uint64_t expected = sizeof kMagic + 8 + key.size() + 8 + size + 8;
  std::vector<uint8_t> file;
  try {
    file = read_file_bytes(path, expected);
  } catch (const Error& e) {
    log::warn(std::string("disk cache: ignoring ") + path + ": " + e.what());
    return std::nullopt;
  }
  const uint8_t* p = file.data();
  const bool intact = file.size() == expected && std::memcmp(p, kMagic, sizeof kMagic) == 0 &&
                      get_u64(p + 8) == key.size() &&
                      std::memcmp(p + 16, key.data(), key.size()) == 0 &&
                      get_u64(p + 16 + key.size()) == size;
  if (!intact) {
    // Another key with the same hash, another version, or a damaged file: computed again.
    log::debug("disk cache: " + path + " does not hold this key; computing it again");
    return std::nullopt;
  }
  const uint8_t* payload = p + 24 + key.size();
  const std::string_view bytes(reinterpret_cast<const char*>(payload), size);
  if (get_u64(payload + size) != checksum(bytes)) {
    log::warn("disk cache: " + path + " is damaged (checksum); computing it again");
    return std::nullopt;
  }
  // The payload moved to the front of the file's own buffer: a large entry is never held twice.
  file.erase(file.begin(), file.begin() + std::ptrdiff_t(payload - p));
  file.resize(size);
  return file;
}

bool DiskCache::write(std::string_view key, std::string_view bytes) const {
  if (!enabled() || key.size() > kMaxKeyBytes) return false;
  std::string file(kMagic, sizeof kMagic);
  file.reserve(sizeof kMagic + 32 + key.size() + bytes.size());
  put_u64(file, key.size());
  file.append(key);
  put_u64(file, bytes.size());
  file.append(bytes);
  put_u64(file, checksum(bytes));
  try {
    std::error_code ec;
    std::filesystem::create_directories(folder_, ec);
    if (ec)
      throw Error(ErrorInfo{.file = folder_, .expected = "a folder for the cache", .found = ec.message()});
    write_file_atomically(path_of(key), file);
    return true;
  } catch (const Error& e) {
    log::warn(std::string("disk cache: not stored: ") + e.what());
    return false;
  }
}

}  // namespace welkin
