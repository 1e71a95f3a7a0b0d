#include "app/module_dirs.h"

#include <filesystem>

#include "welkin/core/module_paths.h"

namespace welkin::editor {

namespace fs = std::filesystem;

namespace {

// The running executable's folder, for the installed presets.
fs::path executable_dir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

}  // namespace

std::unique_ptr<World> make_world_with_plugins() {
  auto world = std::make_unique<World>();
  // The same places as the `welkin` CLI (tools/welkin/session.cpp), from the same compile definitions.
  for (const auto& d : module_search_dirs(WELKIN_MODULE_DIR_FROM_BIN, WELKIN_BUILD_MODULE_DIR, WELKIN_BUILD_BIN_DIR)) world->modules().add_search_dir(d);
  return world;
}

std::vector<PresetFolder> extra_preset_folders() {
  std::error_code ec;
  fs::path installed = (executable_dir() / WELKIN_EDITOR_PRESET_DIR_FROM_BIN).lexically_normal();
  fs::path root = fs::is_directory(installed, ec) ? installed : fs::path(WELKIN_SOURCE_PRESET_DIR);
  return {PresetFolder{"core", root / "core"}};
}

}  // namespace welkin::editor
