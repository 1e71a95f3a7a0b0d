#pragma once
// Where a program looks for plugin modules: the WELKIN_MODULE_PATH entries (colon-separated) first,
// then `relative_to_executable` resolved beside the running executable (the install tree), then
// `build_tree_dir`, but only while the executable runs from `build_bin_dir` (an installed program
// never reads the build tree it came from). Every front end (welkin, welkin-editor) uses this.
#include <string>
#include <vector>

namespace welkin {

std::vector<std::string> module_search_dirs(const std::string& relative_to_executable,
                                            const std::string& build_tree_dir,
                                            const std::string& build_bin_dir);

}  // namespace welkin
