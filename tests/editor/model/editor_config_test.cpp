// Editor state between runs: where it lives, round trip, leniency, and that a broken file is kept.
#include "model/editor_config.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "test_module.h"

namespace {

using namespace welkin::editor;
using editor_test::ScratchDir;

TEST(EditorConfig, PathFollowsXdgThenHome) {
  std::string old_xdg = std::getenv("XDG_CONFIG_HOME") ? std::getenv("XDG_CONFIG_HOME") : "";
  std::string old_home = std::getenv("HOME") ? std::getenv("HOME") : "";
  ::setenv("XDG_CONFIG_HOME", "/x/config", 1);
  EXPECT_EQ(editor_config_path(), std::filesystem::path("/x/config/welkin/editor.json"));
  ::unsetenv("XDG_CONFIG_HOME");
  ::setenv("HOME", "/home/artist", 1);
  EXPECT_EQ(editor_config_path(), std::filesystem::path("/home/artist/.config/welkin/editor.json"));
  if (!old_xdg.empty()) ::setenv("XDG_CONFIG_HOME", old_xdg.c_str(), 1);
  ::setenv("HOME", old_home.c_str(), 1);
}

TEST(EditorConfig, SaveThenLoadRoundTrips) {
  ScratchDir dir("config");
  EditorConfig c;
  c.last_scene = "assets/scenes/default.json";
  c.window_width = 1280;
  c.window_height = 720;
  c.imgui_layout = "[Window][Viewport]\nPos=0,0\n";
  c.panels = {{"Profiler", false}, {"Presets", true}};
  c.view = ViewPose{{1.5, -2.25, 1e6}, 270.0, -12.5};
  c.view_scene = c.last_scene;
  c.fly_speed_multiplier = 4;
  c.look_through_scene_camera = true;
  auto file = dir.path() / "nested" / "welkin" / "editor.json";  // folders are created
  save_editor_config(file, c);
  std::vector<std::string> warnings;
  EXPECT_EQ(load_editor_config(file, warnings), c);
  EXPECT_TRUE(warnings.empty());
}

TEST(EditorConfig, MissingFileGivesDefaults) {
  std::vector<std::string> warnings;
  EXPECT_EQ(load_editor_config("/nonexistent/welkin/editor.json", warnings), EditorConfig{});
  EXPECT_TRUE(warnings.empty());
}

TEST(EditorConfig, WrongTypesAreSkippedWithAWarning) {
  std::vector<std::string> warnings;
  auto c = editor_config_from_json(nlohmann::json::parse(R"({"last_scene": 5, "window": {"width": 800},
                                                            "view": {"position_m": [1, 2]}})"), warnings);
  EXPECT_EQ(c.last_scene, "");
  EXPECT_EQ(c.window_width, 800);
  EXPECT_FALSE(c.view.has_value());
  EXPECT_EQ(warnings.size(), 2u);
}

TEST(EditorConfig, ABrokenFileIsKeptAside) {
  ScratchDir dir("config-broken");
  auto file = dir.write("editor.json", "{\"last_scene\": ");
  std::vector<std::string> warnings;
  EXPECT_EQ(load_editor_config(file, warnings), EditorConfig{});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(editor_test::read_bytes(file.string() + ".bad"), "{\"last_scene\": ");
}

}  // namespace
