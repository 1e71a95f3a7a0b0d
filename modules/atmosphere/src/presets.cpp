#include "welkin/atmosphere/presets.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace welkin::atmosphere {

std::filesystem::path preset_dir(const std::filesystem::path& module_data_dir) {
  return module_data_dir / "presets";
}

std::vector<std::string> preset_names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Atmosphere load_preset_file(const std::filesystem::path& file) {
  Atmosphere a;
  try {
    object_from_json(type_desc<Atmosphere>(), &a, read_json_file(file.string()));  // runs validate()
  } catch (const Error& e) {
    throw e.info().file.empty() ? e.with_file(file.string()) : e;
  }
  return a;
}

}  // namespace welkin::atmosphere
