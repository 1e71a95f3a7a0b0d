#include "welkin/core/module_paths.h"

#include <cstdlib>
#include <filesystem>

namespace welkin {

std::vector<std::string> module_search_dirs(const std::string& relative_to_executable,
                                            const std::string& build_tree_dir,
                                            const std::string& build_bin_dir) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("WELKIN_MODULE_PATH")) {
    std::string s = env;
    for (size_t start = 0; start <= s.size();) {
      size_t end = s.find(':', start);
      if (end == std::string::npos) end = s.size();
      if (end > start) dirs.push_back(s.substr(start, end - start));
      start = end + 1;
    }
  }
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return dirs;
  dirs.push_back((exe.parent_path() / relative_to_executable).lexically_normal().string());
  const bool in_build_tree =
      !build_bin_dir.empty() && std::filesystem::equivalent(exe.parent_path(), build_bin_dir, ec);
  if (in_build_tree && !build_tree_dir.empty() &&
      !std::filesystem::equivalent(dirs.back(), build_tree_dir, ec))
    dirs.push_back(build_tree_dir);
  return dirs;
}

}  // namespace welkin
