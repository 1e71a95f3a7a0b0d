#pragma once
// Every file Welkin reads or writes goes through these functions, so the rules hold everywhere:
// - reads open regular files only (a FIFO or a device is refused at once, never blocks) and never
//   take more than a stated number of bytes;
// - writes are atomic: a temporary file created exclusively beside the target, every write, the
//   close and an fsync checked, then a rename over the target and an fsync of its folder. On any
//   failure the old file is untouched and one Error names the file. An existing file's mode is
//   kept; writing through a symbolic link replaces the file the link points at, not the link.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace welkin {

// Default cap for whole-file reads that state no limit of their own.
inline constexpr uint64_t kMaxInputFileBytes = 1ull << 30;

// Reads the whole regular file `path` of at most `max_bytes` bytes. Throws Error naming the file.
std::string read_file_text(const std::string& path, uint64_t max_bytes = kMaxInputFileBytes);
std::vector<uint8_t> read_file_bytes(const std::string& path, uint64_t max_bytes = kMaxInputFileBytes);

// Replaces (or creates) `path` with `bytes`, atomically as described above. Throws Error.
void write_file_atomically(const std::string& path, std::string_view bytes);
inline void write_file_atomically(const std::string& path, const std::vector<uint8_t>& bytes) {
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace welkin
