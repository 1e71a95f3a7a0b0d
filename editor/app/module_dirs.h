#pragma once
// Where the editor finds plugin modules and the presets of modules without a data folder: the same
// places as the `welkin` CLI (welkin::module_search_dirs: WELKIN_MODULE_PATH, then beside the
// executable, then the build tree).
#include <memory>
#include <string>
#include <vector>

#include "model/preset_library.h"
#include "welkin/core/world.h"

namespace welkin::editor {

// An empty world that knows every installed module (loaded on demand).
std::unique_ptr<World> make_world_with_plugins();
// Preset folders for modules that have no data folder: the built-in "core" module's presets
// (installed share/welkin/presets/core, else the source tree's assets/presets/core).
std::vector<PresetFolder> extra_preset_folders();

}  // namespace welkin::editor
