#pragma once
// Where a program looks for plugin modules: the WELKIN_MODULE_PATH entries (colon-separated) first,
// then `relative_to_executable` resolved beside the running executable (the install tree), then
// `build_tree_dir` (running from a build folder). Every front end (welkin, welkin-editor) uses this.
#include <string>
#include <vector>

namespace welkin {

std::vector<std::string> module_search_dirs(const std::string& relative_to_executable, const std::string& build_tree_dir);

}  // namespace welkin
