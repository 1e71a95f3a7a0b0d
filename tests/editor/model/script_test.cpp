// Editor scripts: parsing (quotes, comments, variables, line numbers) and the document verbs.
#include "model/script.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "test_module.h"
#include "welkin/core/error.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
// The editor's timeline document, not the runtime's welkin::Sequence that it converts to.
using welkin::editor::load_sequence_file;
using editor_test::ScratchDir;
using nlohmann::json;

TEST(ScriptParse, WordsQuotesCommentsAndTails) {
  auto lines = parse_script("# a comment\n\nselect \"near ball\"  # trailing\nset core.DebugShape/albedo [0.1, 0.2, 0.3]\r\n", "s.txt");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].number, 3);
  EXPECT_EQ(lines[0].verb, "select");
  EXPECT_EQ(lines[0].args, std::vector<std::string>{"near ball"});
  EXPECT_EQ(lines[1].args[0], "core.DebugShape/albedo");
  EXPECT_EQ(lines[1].tail(1), "[0.1, 0.2, 0.3]");
  EXPECT_EQ(lines[1].where(), "s.txt:4");
}

TEST(ScriptParse, ExpandsEnvironmentVariables) {
  ::setenv("WELKIN_SCRIPT_TEST_DIR", "/tmp/out dir", 1);
  auto lines = parse_script("screenshot \"${WELKIN_SCRIPT_TEST_DIR}/a.png\"\nsave-scene $WELKIN_SCRIPT_TEST_DIR/b.json\nprint $$5", "s");
  EXPECT_EQ(lines[0].args[0], "/tmp/out dir/a.png");
  EXPECT_EQ(lines[1].args[0], "/tmp/out");  // unquoted: the space splits
  EXPECT_EQ(lines[2].args[0], "$5");
}

TEST(ScriptParse, ErrorsNameFileAndLine) {
  try {
    parse_script("undo\nselect \"open", "bad.txt");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.info().file, "bad.txt:2");
  }
  ::unsetenv("WELKIN_SCRIPT_TEST_UNSET");
  EXPECT_THROW(parse_script("load-scene $WELKIN_SCRIPT_TEST_UNSET/x", "s"), Error);
}

class ScriptRun : public ::testing::Test {
 protected:
  ScriptRun() : dir("script"), doc(editor_test::make_test_world), presets(editor_test::make_test_world()) {
    presets.add_folder(PresetFolder{"core", WELKIN_SOURCE_DIR "/assets/presets/core"});
    presets.rescan();
  }
  std::string run(const std::string& text) {
    std::string output;
    for (const ScriptLine& line : parse_script(text, "test.script"))
      if (!run_document_verb(doc, presets, line, output)) throw Error(ErrorInfo{.file = line.where(), .message = "unknown verb " + line.verb});
    return output;
  }
  ScratchDir dir;
  EditorDocument doc;
  PresetLibrary presets;
};

TEST_F(ScriptRun, SetUndoRedoExpect) {
  run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\n"
      "select ball\n"
      "set core.DebugShape/albedo [0.1, 0.2, 0.3]\n"
      "expect core.DebugShape/albedo [0.1, 0.2, 0.3]\n"
      "set core.DebugShape/shape box\n"
      "undo\n"
      "expect core.DebugShape/shape sphere\n"
      "undo\n"
      "expect core.DebugShape/albedo [0.8, 0.3, 0.2]\n"
      "redo\n"
      "expect core.DebugShape/albedo/2 0.3\n");
  EXPECT_THROW(run("expect core.DebugShape/albedo/2 0.4"), Error);
}

TEST_F(ScriptRun, SetOnTheSelectionElseTheFirstEntityWithTheComponent) {
  run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\nselect crate\nset core.DebugShape/size_m/0 4\nselect camera\nset core.DebugShape/size_m/0 5\n");
  EXPECT_EQ(doc.get_field(doc.find_by_name("crate"), "core.DebugShape", "size_m/0"), json(4));
  EXPECT_EQ(doc.get_field(doc.find_by_name("ball"), "core.DebugShape", "size_m/0"), json(5));
}

TEST_F(ScriptRun, PresetsSaveAndReloadInAnotherDocument) {
  auto out = dir.path() / "light.json";
  run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\n"
      "set core.DirectionalLight/elevation_deg 12.5\n"
      "save-preset-as core.DirectionalLight \"" + out.string() + "\"\n");
  EditorDocument other(editor_test::make_test_world);
  other.load_scene(WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  std::string output;
  for (const ScriptLine& line : parse_script("load-preset core.DirectionalLight \"" + out.string() +
                                                 "\"\nexpect core.DirectionalLight/elevation_deg 12.5\n", "b"))
    ASSERT_TRUE(run_document_verb(other, presets, line, output));
}

TEST_F(ScriptRun, ApplyAndBlendShippedPresets) {
  std::string first = presets.presets_for("core.DirectionalLight").at(0)->name;
  std::string second = presets.presets_for("core.DirectionalLight").at(1)->name;
  std::string out = run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\n"
                        "apply-preset core " + first + "\n"
                        "diff-preset core " + first + "\n"
                        "blend-presets core " + first + " " + second + " 0.5\n"
                        "undo\nundo\n"
                        "expect core.DirectionalLight/elevation_deg 30\n");
  EXPECT_NE(out.find("differs in 0 field(s)"), std::string::npos) << out;
}

// A preset in a sub-folder, of one element of an array: added, applied over an element, compared.
TEST_F(ScriptRun, ElementPresetsInSubFoldersByPath) {
  editor_test::test_module_data_dir() = dir.path().string();
  dir.write("presets/layers/wispy.json", R"({"coverage": 0.1, "octaves": 2})");
  PresetLibrary library(editor_test::make_test_world());
  library.rescan();
  doc.add_entity("deck", json{{"test.Clouds", json::object()}});
  std::string output;
  auto run_here = [&](const std::string& text) {
    for (const ScriptLine& line : parse_script(text, "test.script"))
      if (!run_document_verb(doc, library, line, output))
        throw Error(ErrorInfo{.file = line.where(), .message = "unknown verb"});
  };
  run_here(
      "apply-preset test layers/wispy\n"
      "expect test.Clouds/layers/1/octaves 2\n"
      "set test.Clouds/layers/0/octaves 7\n"
      "diff-preset test layers/wispy 0\n"
      "apply-preset test layers/wispy 0\n"
      "expect test.Clouds/layers/0/octaves 2\n"
      "diff-preset test layers/wispy 0\n");
  EXPECT_NE(output.find("test/layers/wispy differs in 2 field(s) coverage octaves"), std::string::npos)
      << output;
  EXPECT_NE(output.find("test/layers/wispy differs in 0 field(s)"), std::string::npos) << output;
  EXPECT_THROW(run_here("apply-preset test layers/wispy 9"), Error);
  EXPECT_THROW(run_here("apply-preset test layers/wispy -1"), Error);
  EXPECT_THROW(run_here("apply-preset test layers/wispy one"), Error);
}

TEST_F(ScriptRun, TimelineVerbs) {
  std::string seq = (dir.path() / "day.json").string();
  run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\n"
      "key core.DirectionalLight/elevation_deg 0 -4\n"
      "key core.DirectionalLight/elevation_deg 10 16\n"
      "time 5\n"
      "expect core.DirectionalLight/elevation_deg 6\n"
      "save-sequence \"" + seq + "\"\n"
      "unkey core.DirectionalLight/elevation_deg 10\n"
      "undo\n"
      "time 10\n"
      "expect core.DirectionalLight/elevation_deg 16\n");
  EXPECT_EQ(load_sequence_file(seq).tracks.at(0).entity, "sun");
}

TEST_F(ScriptRun, UsageAndUnknownEntityErrorsNameTheLine) {
  run("load-scene " WELKIN_SOURCE_DIR "/assets/scenes/debug.json\n");
  try {
    run("select camera\nselect nobody\n");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.info().file, "test.script:2");
  }
  EXPECT_THROW(run("set core.Camera/ev100"), Error);
  EXPECT_THROW(run("apply-preset core no-such-preset"), Error);
  std::string output;
  EXPECT_FALSE(run_document_verb(doc, presets, parse_script("screenshot x.png", "s")[0], output));
}

}  // namespace
