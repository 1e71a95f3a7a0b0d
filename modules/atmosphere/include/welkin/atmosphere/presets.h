#pragma once
// Atmosphere presets: JSON objects of atmosphere.Atmosphere fields in the module's presets/ folder.
// Fields a preset leaves out keep the defaults (Earth), so a preset states only what differs.
#include <filesystem>
#include <string>
#include <vector>

#include "welkin/atmosphere/components.h"

namespace welkin::atmosphere {

// The presets/ folder of the module (source tree or installed data folder).
std::filesystem::path preset_dir(const std::filesystem::path& module_data_dir);
// Names (file stems) of the presets in a folder, sorted.
std::vector<std::string> preset_names(const std::filesystem::path& dir);
// Reads and validates a preset file; throws welkin::Error naming the file and JSON path.
Atmosphere load_preset_file(const std::filesystem::path& file);

}  // namespace welkin::atmosphere
