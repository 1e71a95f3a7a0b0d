#pragma once
// Scene documents: JSON with entities and their named components. Loading validates every value
// and loads the modules the components need; saving writes all fields through the atomic writer,
// so it never loses the old file.
//
// { "welkin_scene": 1,
//   "entities": [ { "name": "camera", "components": { "core.Camera": { "vertical_fov_deg": 60 } } } ] }
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "welkin/core/files.h"  // write_file_atomically, used by every saver
#include "welkin/core/world.h"

namespace welkin {

inline constexpr int kSceneFormatVersion = 1;

// Display name of an entity (optional; editors and messages use it).
struct Name {
  static constexpr std::string_view kTypeName = "core.Name";
  std::string value;
};
void describe(TypeBuilder<Name>& t);

// The scene's explicit "modules" list as loaded, so a save writes back everything the file held
// (a module listed without a component in the scene would otherwise be dropped).
struct SceneModules {
  static constexpr std::string_view kTypeName = "core.SceneModules";
  std::vector<std::string> names;
};

// Loads entities into `world`. `file` names the document in error messages.
void load_scene(World& world, const nlohmann::json& doc, const std::string& file);
void load_scene_file(World& world, const std::string& path);
nlohmann::json save_scene(const World& world);
void save_scene_file(const World& world, const std::string& path);

// Component names a scene document uses, without loading anything (for `welkin info`).
std::vector<std::string> scene_component_names(const nlohmann::json& doc, const std::string& file);

}  // namespace welkin
