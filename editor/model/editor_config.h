#pragma once
// Editor state remembered between runs (window and panel layout, last scene, viewport camera), in
// $XDG_CONFIG_HOME/welkin/editor.json (else ~/.config/welkin/editor.json), written atomically.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/fly_camera.h"

namespace welkin::editor {

struct EditorConfig {
  std::string last_scene;
  int window_width = 1600, window_height = 900;
  std::string imgui_layout;        // Dear ImGui's .ini text: window positions and sizes
  std::map<std::string, bool> panels;  // panel title -> open
  std::optional<ViewPose> view;    // the viewport camera of `view_scene`
  std::string view_scene;
  double fly_speed_multiplier = 1;
  bool look_through_scene_camera = false;
  friend bool operator==(const EditorConfig&, const EditorConfig&) = default;
};

// Sections ("[Window][Viewport]" lines) of a Dear ImGui .ini text, and the most a config may hold:
// ImGui's reader is quadratic in them; the editor's own windows and popups are a few dozen.
size_t layout_sections(std::string_view ini);
inline constexpr size_t kMaxLayoutSections = 1024;

// Empty when neither XDG_CONFIG_HOME nor HOME is set.
std::filesystem::path editor_config_path();

nlohmann::json editor_config_to_json(const EditorConfig& config);
// Lenient: a value of the wrong type is skipped with a warning; the rest is kept.
EditorConfig editor_config_from_json(const nlohmann::json& doc, std::vector<std::string>& warnings);
// Defaults when the file is missing. A file that does not parse is copied to <file>.bad (so the
// next save cannot lose it) and defaults are returned with a warning.
EditorConfig load_editor_config(const std::filesystem::path& file, std::vector<std::string>& warnings);
// Creates the folder when needed; temporary file, then rename. Throws Error.
void save_editor_config(const std::filesystem::path& file, const EditorConfig& config);

}  // namespace welkin::editor
