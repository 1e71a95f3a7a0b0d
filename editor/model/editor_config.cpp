#include "model/editor_config.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kConfigVersion = 1;

template <class T> void read_value(const json& doc, const char* key, T& out, std::vector<std::string>& warnings) {
  auto it = doc.find(key);
  if (it == doc.end()) return;
  try {
    out = it->get<T>();
  } catch (const json::exception&) {
    warnings.push_back(std::string("editor config: ignoring /") + key + " (" + describe_json(*it) + ")");
  }
}

}  // namespace

size_t layout_sections(std::string_view ini) {
  size_t n = 0;
  for (size_t i = 0; i < ini.size(); ++i)
    if (ini[i] == '[' && (i == 0 || ini[i - 1] == '\n')) ++n;
  return n;
}

fs::path editor_config_path() {
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return fs::path(xdg) / "welkin" / "editor.json";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".config" / "welkin" / "editor.json";
  return {};
}

json editor_config_to_json(const EditorConfig& c) {
  json j{{"welkin_editor_config", kConfigVersion},
         {"last_scene", c.last_scene},
         {"window", {{"width", c.window_width}, {"height", c.window_height}}},
         {"imgui_layout", c.imgui_layout},
         {"panels", c.panels},
         {"fly_speed_multiplier", c.fly_speed_multiplier},
         {"look_through_scene_camera", c.look_through_scene_camera}};
  if (c.view) {
    j["view"] = {{"scene", c.view_scene},
                 {"position_m", {c.view->position_m.x, c.view->position_m.y, c.view->position_m.z}},
                 {"heading_deg", c.view->heading_deg},
                 {"pitch_deg", c.view->pitch_deg}};
  }
  return j;
}

EditorConfig editor_config_from_json(const json& doc, std::vector<std::string>& warnings) {
  EditorConfig c;
  if (!doc.is_object()) {
    warnings.push_back("editor config: expected an object, found " + describe_json(doc));
    return c;
  }
  read_value(doc, "last_scene", c.last_scene, warnings);
  if (auto w = doc.find("window"); w != doc.end() && w->is_object()) {
    read_value(*w, "width", c.window_width, warnings);
    read_value(*w, "height", c.window_height, warnings);
    c.window_width = std::clamp(c.window_width, 320, 16384);
    c.window_height = std::clamp(c.window_height, 240, 16384);
  }
  read_value(doc, "imgui_layout", c.imgui_layout, warnings);
  // Dear ImGui 1.86 looks each [Window][...] section of its .ini up in a list of those read so far,
  // so its work grows with the square of the sections: the layout is bounded before it gets there.
  if (size_t sections = layout_sections(c.imgui_layout); sections > kMaxLayoutSections) {
    warnings.push_back("editor config: ignoring /imgui_layout (" + std::to_string(sections) + " sections, at most " +
                       std::to_string(kMaxLayoutSections) + ")");
    c.imgui_layout.clear();
  }
  read_value(doc, "panels", c.panels, warnings);
  read_value(doc, "fly_speed_multiplier", c.fly_speed_multiplier, warnings);
  if (!(c.fly_speed_multiplier > 1e-6 && c.fly_speed_multiplier < 1e6)) c.fly_speed_multiplier = 1;
  read_value(doc, "look_through_scene_camera", c.look_through_scene_camera, warnings);
  if (auto v = doc.find("view"); v != doc.end()) {
    ViewPose pose;
    std::vector<double> p;
    size_t before = warnings.size();
    read_value(*v, "scene", c.view_scene, warnings);
    read_value(*v, "position_m", p, warnings);
    read_value(*v, "heading_deg", pose.heading_deg, warnings);
    read_value(*v, "pitch_deg", pose.pitch_deg, warnings);
    bool finite = std::isfinite(pose.heading_deg) && std::isfinite(pose.pitch_deg);
    for (double x : p) finite = finite && std::isfinite(x);
    if (warnings.size() == before && p.size() == 3 && finite) {
      pose.position_m = {p[0], p[1], p[2]};
      c.view = pose;
    } else if (warnings.size() == before) {
      warnings.push_back("editor config: ignoring /view (expected position_m [x, y, z] and finite angles)");
    }
  }
  return c;
}

EditorConfig load_editor_config(const fs::path& file, std::vector<std::string>& warnings) {
  std::error_code ec;
  if (file.empty() || !fs::exists(file, ec)) return {};
  try {
    return editor_config_from_json(read_json_file(file.string()), warnings);
  } catch (const Error& err) {
    fs::path aside = file;
    aside += ".bad";
    fs::copy_file(file, aside, fs::copy_options::overwrite_existing, ec);
    warnings.push_back("editor config: " + format_error(err.info()) + "; starting with defaults" +
                       (ec ? "" : " (the file was kept as " + aside.string() + ")"));
    return {};
  }
}

void save_editor_config(const fs::path& file, const EditorConfig& config) {
  if (file.empty()) throw Error("editor config: no place to save it (set XDG_CONFIG_HOME or HOME)");
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw Error(ErrorInfo{.file = file.parent_path().string(), .message = "cannot create folder: " + ec.message()});
  write_file_atomically(file.string(), editor_config_to_json(config).dump(2) + "\n");
}

}  // namespace welkin::editor
