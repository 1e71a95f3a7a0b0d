// Presets: found in every module's data folder, component inferred, applied and blended as undoable
// edits, saved atomically, renamed; a malformed file reports file + path and is never written.
#include "model/preset_library.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/module_panels.h"
#include "model/preset_actions.h"
#include "test_module.h"
#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using editor_test::ScratchDir;
using nlohmann::json;

class Presets : public ::testing::Test {
 protected:
  Presets() : dir("presets"), doc(editor_test::make_test_world), library(nullptr) {
    editor_test::test_module_data_dir() = dir.path().string();
    dir.write("presets/thin.json", R"({"density": 0.0, "steps": 8, "altitude_m": 1000, "mode": "fast",
                                       "tint": [0.0, 0.5, 1.0], "shadows": false, "label": "thin",
                                       "layers": [{"coverage": 0.0, "octaves": 2}, {"coverage": 0.25, "octaves": 3}]})");
    dir.write("presets/thick.json", R"({"density": 8.0, "steps": 64, "altitude_m": 3000, "mode": "precise",
                                        "tint": [1.0, 0.5, 0.0], "shadows": true, "label": "thick",
                                        "layers": [{"coverage": 1.0, "octaves": 6}, {"coverage": 0.75, "octaves": 7}]})");
    dir.write("presets/haze.json", R"({"visibility_km": 2.5})");  // a test.Fog preset
    library = PresetLibrary(editor_test::make_test_world());
    library.rescan();
    deck = doc.add_entity("deck", json{{"test.Clouds", json::object()}});
  }
  ScratchDir dir;
  EditorDocument doc;
  PresetLibrary library;
  EntityId deck = kNoEntity;
};

TEST_F(Presets, FindsEachModulesPresetsAndInfersTheirComponent) {
  ASSERT_NE(library.find("test", "thin"), nullptr);
  EXPECT_TRUE(library.find("test", "thin")->ok());
  EXPECT_EQ(library.find("test", "thin")->component, "test.Clouds");
  EXPECT_EQ(library.find("test", "haze")->component, "test.Fog");
  EXPECT_EQ(library.presets_for("test.Clouds").size(), 2u);
  EXPECT_EQ(library.folder_of("test"), dir.path() / "presets");
}

TEST_F(Presets, BrowsingLoadsNoModuleIntoTheScene) {
  EditorDocument fresh(editor_test::make_test_world);
  library.rescan();
  EXPECT_FALSE(fresh.world().modules().is_loaded("test"));
}

TEST_F(Presets, ApplySetsEveryFieldAndUndoes) {
  json before = doc.get_component(deck, "test.Clouds");
  apply_preset(doc, library, *library.find("test", "thick"), deck);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "steps"), json(64));
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "layers/1/octaves"), json(7));
  EXPECT_TRUE(preset_differences(doc, library, *library.find("test", "thick"), deck).empty());
  doc.undo();
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), before);
}

TEST_F(Presets, AFieldThePresetLeavesOutGetsTheDeclaredDefault) {
  dir.write("presets/dense.json", R"({"density": 5})");
  library.rescan();
  doc.set_field(deck, "test.Clouds", "steps", 100);
  apply_preset(doc, library, *library.find("test", "dense"), deck);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "steps"), json(16));
}

TEST_F(Presets, BlendAtAQuarterIsTheExactLerp) {
  blend_presets(doc, library, *library.find("test", "thin"), *library.find("test", "thick"), 0.25, deck);
  auto lerp = [](double a, double b) { return std::lerp(a, b, 0.25); };
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "density").get<double>(), double(float(lerp(0.0, 8.0))));  // 2
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "altitude_m").get<double>(), lerp(1000, 3000));  // f64: 1500
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "steps"), json(std::llround(lerp(8, 64))));  // 22
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "tint"), json::parse("[0.25, 0.5, 0.75]"));
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "layers/1/coverage").get<double>(), double(float(lerp(0.25, 0.75))));
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "layers/1/octaves"), json(std::llround(lerp(3, 7))));
  // Non-numeric fields switch at one half.
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "mode"), json("fast"));
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "label"), json("thin"));
  blend_presets(doc, library, *library.find("test", "thin"), *library.find("test", "thick"), 0.5, deck);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "mode"), json("precise"));
}

TEST_F(Presets, BlendEndpointsAreThePresetsExactly) {
  const PresetFile& thin = *library.find("test", "thin");
  const PresetFile& thick = *library.find("test", "thick");
  blend_presets(doc, library, thin, thick, 0.0, deck);
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), library.complete_value(thin));
  blend_presets(doc, library, thin, thick, 1.0, deck);
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), library.complete_value(thick));
}

TEST_F(Presets, ABlendSliderDragIsOneUndoStep) {
  json before = doc.get_component(deck, "test.Clouds");
  for (double t = 0.0; t <= 1.0; t += 0.125)
    blend_presets(doc, library, *library.find("test", "thin"), *library.find("test", "thick"), t, deck, true);
  doc.end_continuous_edit();
  EXPECT_EQ(doc.history().steps().size(), 2u);  // adding the deck, then the drag
  doc.undo();
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), before);
}

TEST_F(Presets, BlendingPresetsOfDifferentComponentsIsRefused) {
  EXPECT_THROW(blend_presets(doc, library, *library.find("test", "thin"), *library.find("test", "haze"), 0.5, deck), Error);
}

TEST_F(Presets, SaveAsThenReloadRoundTrips) {
  doc.set_field(deck, "test.Clouds", "density", 3.3);
  doc.set_field(deck, "test.Clouds", "tint", json::parse("[0.1, 0.2, 0.3]"));
  doc.set_field(deck, "test.Clouds", "mode", "precise");
  json edited = doc.get_component(deck, "test.Clouds");
  auto file = dir.path() / "presets" / "mine.json";
  save_preset_as(doc, library, "test.Clouds", deck, file);
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp-" + std::to_string(::getpid())));
  const PresetFile* mine = library.find("test", "mine");  // the library rescanned
  ASSERT_NE(mine, nullptr);
  ASSERT_TRUE(mine->ok());
  EXPECT_EQ(library.complete_value(*mine), edited);
  // Another document (another run) applies it and gets the same values.
  EditorDocument other(editor_test::make_test_world);
  EntityId e = other.add_entity("other", json{{"test.Clouds", json::object()}});
  apply_preset(other, library, *mine, e);
  EXPECT_EQ(other.get_component(e, "test.Clouds"), edited);
  EXPECT_EQ(other.get_field(e, "test.Clouds", "density"), json(3.3));
}

TEST_F(Presets, DifferencesNameTheChangedFields) {
  const PresetFile& thick = *library.find("test", "thick");
  apply_preset(doc, library, thick, deck);
  doc.set_field(deck, "test.Clouds", "density", 7.0);
  doc.set_field(deck, "test.Clouds", "layers/1/coverage", 0.5);
  EXPECT_EQ(preset_differences(doc, library, thick, deck), (std::vector<std::string>{"density", "layers/1/coverage"}));
  revert_to_preset_file(doc, library, thick, deck);
  EXPECT_TRUE(preset_differences(doc, library, thick, deck).empty());
  doc.undo();  // the revert is an edit like any other
  EXPECT_EQ(preset_differences(doc, library, thick, deck).size(), 2u);
}

TEST_F(Presets, SaveOverwritesThePresetsOwnFile) {
  apply_preset(doc, library, *library.find("test", "thin"), deck);
  doc.set_field(deck, "test.Clouds", "steps", 12);
  save_preset(doc, library, *library.find("test", "thin"), deck);
  EXPECT_EQ(library.find("test", "thin")->fields["steps"], json(12));
  EXPECT_TRUE(preset_differences(doc, library, *library.find("test", "thin"), deck).empty());
}

TEST_F(Presets, AMalformedPresetReportsFileAndPathAndIsLeftByteIdentical) {
  const std::string text = "{\n  \"density\": 2,\n  \"layers\": [{\"coverage\": 1.5}]\n}\n";  // coverage is in [0, 1]
  auto bad = dir.write("presets/broken.json", text);
  const std::string truncated = "{\"density\": 2, \"ste";
  auto cut = dir.write("presets/cut.json", truncated);
  library.rescan();
  const PresetFile* p = library.find("test", "broken");
  ASSERT_NE(p, nullptr);
  ASSERT_FALSE(p->ok());
  EXPECT_EQ(p->error->file, bad.string());
  EXPECT_EQ(p->error->path, "/layers/0/coverage");
  EXPECT_EQ(p->component, "test.Clouds");
  const PresetFile* c = library.find("test", "cut");
  ASSERT_FALSE(c->ok());
  EXPECT_NE(c->error->file.find("cut.json:1:"), std::string::npos) << c->error->file;  // line and column
  // The other presets still load.
  EXPECT_TRUE(library.find("test", "thin")->ok());
  // Nothing writes over it: not saving to it, not applying it.
  EXPECT_THROW(save_preset_as(doc, library, "test.Clouds", deck, bad), Error);
  EXPECT_THROW(save_preset(doc, library, *library.find("test", "broken"), deck), Error);
  EXPECT_THROW(apply_preset(doc, library, *library.find("test", "broken"), deck), Error);
  EXPECT_EQ(editor_test::read_bytes(bad), text);
  EXPECT_EQ(editor_test::read_bytes(cut), truncated);
  EXPECT_FALSE(doc.history().steps().size() > 1);
}

TEST_F(Presets, AnUnknownKeyIsReportedAgainstTheClosestComponent) {
  dir.write("presets/typo.json", R"({"density": 1, "stepz": 3})");
  library.rescan();
  const PresetFile* p = library.find("test", "typo");
  ASSERT_FALSE(p->ok());
  EXPECT_EQ(p->component, "test.Clouds");
  EXPECT_EQ(p->error->path, "/stepz");
}

TEST_F(Presets, SaveAsRefusesToReplaceAPresetOfAnotherComponent) {
  auto haze = dir.path() / "presets" / "haze.json";
  std::string bytes = editor_test::read_bytes(haze);
  EXPECT_THROW(save_preset_as(doc, library, "test.Clouds", deck, haze), Error);
  EXPECT_EQ(editor_test::read_bytes(haze), bytes);
}

TEST_F(Presets, RenameMovesTheFileAndRefusesClashesAndFolders) {
  auto renamed = library.rename(*library.find("test", "thin"), "wispy");
  EXPECT_EQ(renamed, dir.path() / "presets" / "wispy.json");
  EXPECT_EQ(library.find("test", "thin"), nullptr);
  ASSERT_NE(library.find("test", "wispy"), nullptr);
  EXPECT_THROW(library.rename(*library.find("test", "wispy"), "thick"), Error);
  EXPECT_THROW(library.rename(*library.find("test", "wispy"), "../escape"), Error);
  EXPECT_THROW(library.rename(*library.find("test", "wispy"), ""), Error);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "presets" / "thick.json"));
}

TEST_F(Presets, ExtraFoldersServeModulesWithoutADataFolder) {
  ScratchDir core("core-presets");
  core.write("noon.json", R"({"azimuth_deg": 180, "elevation_deg": 70})");
  library.add_folder(PresetFolder{"core", core.path()});
  library.rescan();
  const PresetFile* noon = library.find("core", "noon");
  ASSERT_NE(noon, nullptr);
  ASSERT_TRUE(noon->ok()) << format_error(*noon->error);
  EXPECT_EQ(noon->component, "core.DirectionalLight");
}

// Sub-folders are searched (the clouds' genera); a preset's name is its path there. Hidden folders and
// files of other kinds are not presets.
TEST_F(Presets, PresetsInSubFoldersAreFoundByTheirPath) {
  dir.write("presets/layers/wispy.json", R"({"coverage": 0.1, "octaves": 2})");
  dir.write("presets/layers/deep/dense.json", R"({"coverage": 0.9})");
  dir.write("presets/.hidden/secret.json", R"({"density": 1})");
  dir.write("presets/layers/notes.txt", "not a preset");
  library.rescan();
  const PresetFile* wispy = library.find("test", "layers/wispy");
  ASSERT_NE(wispy, nullptr);
  ASSERT_TRUE(wispy->ok()) << format_error(*wispy->error);
  EXPECT_EQ(wispy->folder, "layers");
  EXPECT_EQ(wispy->component, "test.Clouds");
  EXPECT_EQ(wispy->element_field, "layers");
  EXPECT_EQ(wispy->target(), "test.Clouds/layers");
  const PresetFile* dense = library.find("test", "layers/deep/dense");
  ASSERT_NE(dense, nullptr);
  EXPECT_EQ(dense->folder, "layers/deep");
  EXPECT_EQ(library.find("test", ".hidden/secret"), nullptr);
  EXPECT_EQ(library.find("test", "wispy"), nullptr);
  EXPECT_EQ(library.presets().size(), 5u);  // thin, thick, haze and the two layers
  // Whole-component presets stay whole: more of their keys are the component's than an element's.
  EXPECT_FALSE(library.find("test", "thick")->is_element());
  EXPECT_EQ(library.presets_for("test.Clouds").size(), 4u);
  // As the browser lists them: the folder's own first, then each sub-folder's.
  std::vector<std::string> listed;
  for (const PresetFile* p : library.presets_in(PresetFolder{"test", dir.path() / "presets"}))
    listed.push_back(p->name);
  EXPECT_EQ(listed, (std::vector<std::string>{"haze", "thick", "thin", "layers/wispy", "layers/deep/dense"}));
}

// An element preset is added as a new element, or applied over a chosen one; each is one undo step,
// the array's bound holds, and it is compared with and saved from an element.
TEST_F(Presets, AnElementPresetAddsAnElementOrReplacesOne) {
  dir.write("presets/layers/wispy.json", R"({"coverage": 0.1, "octaves": 2})");
  library.rescan();
  const PresetFile& wispy = *library.find("test", "layers/wispy");
  json before = doc.get_component(deck, "test.Clouds");
  ASSERT_EQ(before["layers"].size(), 1u);
  apply_preset(doc, library, wispy, deck);
  json after = doc.get_component(deck, "test.Clouds");
  ASSERT_EQ(after["layers"].size(), 2u);
  EXPECT_EQ(after["layers"][0], before["layers"][0]);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "layers/1/octaves"), json(2));
  EXPECT_NEAR(doc.get_field(deck, "test.Clouds", "layers/1/coverage").get<double>(), 0.1, 1e-7);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "density"), before["density"]);  // the rest is left alone
  EXPECT_EQ(element_count(doc, wispy, deck), 2u);
  doc.undo();
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), before);

  apply_preset_to_element(doc, library, wispy, deck, 0);
  EXPECT_EQ(doc.get_field(deck, "test.Clouds", "layers/0/octaves"), json(2));
  EXPECT_EQ(doc.get_component(deck, "test.Clouds")["layers"].size(), 1u);
  EXPECT_TRUE(preset_element_differences(doc, library, wispy, deck, 0).empty());
  doc.set_field(deck, "test.Clouds", "layers/0/octaves", 5);
  EXPECT_EQ(preset_element_differences(doc, library, wispy, deck, 0), (std::vector<std::string>{"octaves"}));
  try {
    apply_preset_to_element(doc, library, wispy, deck, 3);
    FAIL() << "element 3 of 1 was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.info().path, "test.Clouds/layers/3");
  }

  // The array's bound (4) holds: the fifth layer is refused and changes nothing.
  for (int i = 0; i < 3; ++i) apply_preset(doc, library, wispy, deck);
  json full = doc.get_component(deck, "test.Clouds");
  EXPECT_EQ(full["layers"].size(), 4u);
  EXPECT_THROW(apply_preset(doc, library, wispy, deck), Error);
  EXPECT_EQ(doc.get_component(deck, "test.Clouds"), full);

  // Saved from element 0 (octaves 5), read back.
  save_preset_element(doc, library, wispy, deck, 0);
  const PresetFile* saved = library.find("test", "layers/wispy");
  ASSERT_NE(saved, nullptr);
  EXPECT_EQ(saved->fields["octaves"], json(5));
  EXPECT_TRUE(saved->is_element());

  // What applies to whole components only is refused, not done to the wrong thing.
  EXPECT_THROW(save_preset(doc, library, *saved, deck), Error);
  EXPECT_THROW(revert_to_preset_file(doc, library, *saved, deck), Error);
  EXPECT_THROW(blend_presets(doc, library, *saved, *saved, 0.5, deck), Error);
  EXPECT_THROW(apply_preset_to_element(doc, library, *library.find("test", "thin"), deck, 0), Error);
  EXPECT_EQ(editor_test::read_bytes(dir.path() / "presets" / "thin.json").find("\"octaves\": 5"),
            std::string::npos);
}

// An entity without the component gains it with its declared defaults and the new element after them.
TEST_F(Presets, AnElementPresetAddsTheComponentWhenItIsMissing) {
  dir.write("presets/layers/wispy.json", R"({"coverage": 0.1, "octaves": 2})");
  library.rescan();
  EntityId bare = doc.add_entity("bare");
  apply_preset(doc, library, *library.find("test", "layers/wispy"), bare);
  json c = doc.get_component(bare, "test.Clouds");
  ASSERT_EQ(c["layers"].size(), 2u);  // the declared default layer, then the preset's
  EXPECT_EQ(c["layers"][1]["octaves"], json(2));
  EXPECT_EQ(c["steps"], json(16));
}

TEST_F(Presets, TheShippedCorePresetsAllLoad) {
  library.add_folder(PresetFolder{"core", WELKIN_SOURCE_DIR "/assets/presets/core"});
  library.rescan();
  size_t core = 0;
  for (const PresetFile& p : library.presets()) {
    if (p.module != "core") continue;
    ++core;
    EXPECT_TRUE(p.ok()) << format_error(*p.error);
  }
  EXPECT_GE(core, 2u);
}

}  // namespace

namespace {

using namespace welkin;
using namespace welkin::editor;

TEST(ModulePanels, AModuleDeclaresPanelsAsData) {
  ScratchDir dir("panels");
  editor_test::test_module_data_dir() = dir.path().string();
  auto world = editor_test::make_test_world();
  std::vector<std::string> errors;
  EXPECT_TRUE(read_module_panels(world->modules(), errors).empty());  // no file: no panels
  dir.write("editor/panels.json", R"({"panels": [{"title": "Sky", "components": ["test.Clouds", "test.Fog"]}]})");
  auto specs = read_module_panels(world->modules(), errors);
  EXPECT_TRUE(errors.empty());
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_EQ(specs[0], (ModulePanelSpec{"test", "Sky", {"test.Clouds", "test.Fog"}}));
}

TEST(ModulePanels, ABadFileIsSkippedWithItsPath) {
  ScratchDir dir("panels-bad");
  editor_test::test_module_data_dir() = dir.path().string();
  dir.write("editor/panels.json", R"({"panels": [{"title": "Sky", "components": ["other.Thing"]}]})");
  auto world = editor_test::make_test_world();
  std::vector<std::string> errors;
  EXPECT_TRUE(read_module_panels(world->modules(), errors).empty());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("/panels/0/components/0"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("panels.json"), std::string::npos) << errors[0];
}

}  // namespace
