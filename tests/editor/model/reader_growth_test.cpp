// The editor's readers (presets, the editor config, module panels) do work linear in their input:
// each is fed 1x, 10x and 100x a pathological file and its time may grow by about 10x per step, not
// 100x (tests/support/growth.h). Each refuses a bad file with one error naming the file and path.
#include <gtest/gtest.h>

#include "growth.h"
#include "model/editor_config.h"
#include "model/module_panels.h"
#include "model/preset_library.h"
#include "test_module.h"
#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using editor_test::ScratchDir;
using nlohmann::json;
using welkin::testing::measure_growth;

class ReaderGrowth : public ::testing::Test {
 protected:
  ReaderGrowth() : dir("reader-growth"), library(nullptr) {
    editor_test::test_module_data_dir() = dir.path().string();
    library = PresetLibrary(editor_test::make_test_world());
  }
  // Writes the text to a file of its own (outside the timed part).
  std::filesystem::path file_of(const std::string& text) {
    return dir.write("inputs/" + std::to_string(files++) + ".json", text);
  }
  ScratchDir dir;
  PresetLibrary library;
  int files = 0;
};

TEST_F(ReaderGrowth, PresetWithManyUnknownKeysAndALongString) {
  // The module's components are matched against every key, then the file is refused at its first
  // unknown key.
  auto make = [&](size_t n) {
    std::string s = R"({"density": 1, "label": ")" + std::string(n * 20, 'l') + "\"";
    for (size_t i = 0; i < n; ++i) s += ", \"unknown" + std::to_string(i) + "\": " + std::to_string(i);
    return file_of(s + "}");
  };
  auto read = [&](const std::filesystem::path& f) { return library.read("test", f); };
  auto g = measure_growth(300, make, read);
  EXPECT_TRUE(g.linear()) << g.describe();
  PresetFile p = read(make(5));
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error->file, p.file.string());
  EXPECT_EQ(p.error->path, "/unknown0");
}

TEST_F(ReaderGrowth, PresetWithManyLayersIsRefusedAtTheBound) {
  auto make = [&](size_t n) {
    std::string s = R"({"layers": [)";
    for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + std::string(R"({"coverage": 0.5, "octaves": 3})");
    return file_of(s + "]}");
  };
  auto read = [&](const std::filesystem::path& f) { return library.read_for_component("test.Clouds", f); };
  auto g = measure_growth(200, make, read);
  EXPECT_TRUE(g.linear()) << g.describe();
  PresetFile p = read(make(5));
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error->path, "/layers");
  EXPECT_EQ(p.error->expected, "at most 4 elements");
}

TEST_F(ReaderGrowth, EditorConfigWithManyPanelsAndALongLayout) {
  // A layout of many ImGui sections is dropped with a warning: Dear ImGui's own reader would spend
  // the square of them.
  auto make = [](size_t n) {
    json panels = json::object();
    std::string layout;
    for (size_t i = 0; i < n; ++i) {
      panels["panel " + std::to_string(i)] = i % 2 == 0;
      layout += "[Window][W" + std::to_string(i) + "]\nPos=0,0\nSize=100,100\n\n";
    }
    return json{{"welkin_editor_config", 1},
                {"last_scene", std::string(n * 10, 's')},
                {"panels", std::move(panels)},
                {"imgui_layout", std::move(layout)}}
        .dump();
  };
  auto read = [](const std::string& text) {
    std::vector<std::string> warnings;
    EditorConfig c = editor_config_from_json(parse_json_text(text, "editor.json"), warnings);
    return std::pair{c, warnings};
  };
  auto g = measure_growth(100, make, read);
  EXPECT_TRUE(g.linear()) << g.describe();
  auto [small, none] = read(make(10));
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(layout_sections(small.imgui_layout), 10u);
  EXPECT_EQ(small.panels.size(), 10u);
  auto [big, warnings] = read(make(kMaxLayoutSections + 1));
  EXPECT_TRUE(big.imgui_layout.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("/imgui_layout (1025 sections, at most 1024)"), std::string::npos)
      << warnings[0];
}

TEST_F(ReaderGrowth, ModulePanelsWithManyPanelsAndComponents) {
  auto make = [&](size_t n) {
    json panels = json::array();
    for (size_t i = 0; i < n; ++i)
      panels.push_back(
          {{"title", "P" + std::to_string(i)}, {"components", {"test.Clouds", "test.Fog", "test.Weather"}}});
    panels.push_back({{"title", "last"}, {"components", {"test.Clouds", "other.Thing"}}});
    return json{{"panels", std::move(panels)}}.dump();
  };
  auto world = editor_test::make_test_world();
  auto read = [&](const std::string& text) {
    dir.write("editor/panels.json", text);
    std::vector<std::string> errors;
    read_module_panels(world->modules(), errors);
    return errors;
  };
  auto g = measure_growth(100, make, read);
  EXPECT_TRUE(g.linear()) << g.describe();
  std::vector<std::string> errors = read(make(3));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("panels.json: at /panels/3/components/1"), std::string::npos) << errors[0];
}

}  // namespace
