#pragma once
// Scratch folders for a test process. Each is new, made by mkdtemp: a name built from the process id
// alone is taken again once ids wrap, and then a test meets files an earlier run left there (a crashed
// run, or another checkout on the same machine). The folders are removed when the process ends.
#include <stdlib.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

namespace welkin::testing {

namespace detail {
class ScratchFolders {
 public:
  ~ScratchFolders() {
    for (const auto& [prefix, folder] : made_) {
      std::error_code ignored;
      std::filesystem::remove_all(folder, ignored);
    }
  }
  const std::filesystem::path& get(const std::string& prefix) {
    if (auto it = made_.find(prefix); it != made_.end()) return it->second;
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a scratch folder " + pattern);
    return made_.emplace(prefix, pattern).first->second;
  }

 private:
  std::map<std::string, std::filesystem::path> made_;
};
}  // namespace detail

// The process's own folder for `prefix`: the same folder on every call, new at the first.
inline const std::filesystem::path& scratch_folder(const std::string& prefix) {
  static detail::ScratchFolders folders;
  return folders.get(prefix);
}

// A file name in the process's own folder for `prefix`.
inline std::filesystem::path scratch_path(const std::string& prefix, const std::string& name) {
  return scratch_folder(prefix) / name;
}

}  // namespace welkin::testing
