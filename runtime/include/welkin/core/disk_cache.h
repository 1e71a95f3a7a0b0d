#pragma once
// Results that cost more to compute than to read (LUTs that depend only on a planet's air), kept
// between runs in files named by a hash of everything they depend on. The key is the whole
// description, not only its hash: a file is used only when it holds exactly the key asked for, the
// size expected and a matching checksum, so a collision, a truncated or damaged file, or a file from
// another version reads as a miss and the result is computed again (and stored again). The cache
// is an optimisation: a failure to write it is logged, never an error.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace welkin {

class DiskCache {
 public:
  // $WELKIN_CACHE_DIR when set (set and empty: no cache), else $XDG_CACHE_HOME/welkin, else
  // $HOME/.cache/welkin; no cache when none of them is set.
  static DiskCache from_environment();
  explicit DiskCache(std::string folder = {});  // empty: disabled

  bool enabled() const { return !folder_.empty(); }
  const std::string& folder() const { return folder_; }
  // The file that holds `key` (whether or not it exists).
  std::string path_of(std::string_view key) const;

  // The bytes stored under `key`, when a file holds exactly that key and `size` bytes, checksum intact.
  std::optional<std::vector<uint8_t>> read(std::string_view key, size_t size) const;
  // Stores `bytes` under `key` (atomically: files.h); false, with a warning logged, when it could not.
  bool write(std::string_view key, std::string_view bytes) const;

  // FNV-1a, 64 bits: names the files (their contents are checked by zlib's CRC-32).
  static uint64_t hash(std::string_view bytes, uint64_t seed = 14695981039346656037ull);

 private:
  std::string folder_;
};

}  // namespace welkin
