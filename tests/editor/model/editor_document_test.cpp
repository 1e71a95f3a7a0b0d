// The document: every edit applies at once, is one undo step, and undo/redo restore exact JSON.
#include "model/editor_document.h"

#include <gtest/gtest.h>

#include "test_module.h"
#include "welkin/core/error.h"
#include "welkin/gfx/camera.h"
#include "welkin/scene/scene_file.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using editor_test::ScratchDir;
using nlohmann::json;

const char* kDebugScene = WELKIN_SOURCE_DIR "/assets/scenes/debug.json";

class Document : public ::testing::Test {
 protected:
  Document() : doc(editor_test::make_test_world) { doc.load_scene(kDebugScene); }
  EditorDocument doc;
};

TEST_F(Document, LoadsTheSceneWithNamedEntitiesInFileOrder) {
  auto rows = doc.entities();
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].name, "camera");
  EXPECT_EQ(rows[3].name, "ball");
  EXPECT_EQ(doc.find_by_name("crate"), rows[4].id);
  EXPECT_FALSE(doc.dirty());
}

TEST_F(Document, SetUndoRedoRestoresTheExactJson) {
  EntityId cam = doc.find_by_name("camera");
  json original = doc.get_field(cam, "core.Camera", "ev100");
  EXPECT_EQ(original, json(13.5));
  doc.set_field(cam, "core.Camera", "ev100", 9.25);
  EXPECT_EQ(doc.get_field(cam, "core.Camera", "ev100"), json(9.25));
  EXPECT_FLOAT_EQ(doc.world().registry().get<Camera>(doc.entity(cam))->ev100, 9.25f);  // live in the world
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.get_field(cam, "core.Camera", "ev100"), original);
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(doc.get_field(cam, "core.Camera", "ev100"), json(9.25));
  EXPECT_TRUE(doc.dirty());
}

TEST_F(Document, VectorElementPathsEditOneComponent) {
  EntityId ball = doc.find_by_name("ball");
  doc.set_field(ball, "core.DebugShape", "albedo/1", 0.75);
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "albedo"), json::parse("[0.8, 0.75, 0.2]"));
  doc.undo();
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "albedo"), json::parse("[0.8, 0.3, 0.2]"));
}

TEST_F(Document, ARejectedValueThrowsWithItsPathAndChangesNothing) {
  EntityId ball = doc.find_by_name("ball");
  json before = doc.get_component(ball, "core.DebugShape");
  try {
    doc.set_field(ball, "core.DebugShape", "albedo", json::parse("[0.5, 0.5, 7]"));  // colour range is [0, 1]
    FAIL() << "accepted an out-of-range colour";
  } catch (const Error& e) {
    EXPECT_NE(e.info().path.find("core.DebugShape"), std::string::npos) << e.info().path;
    EXPECT_NE(e.info().path.find("albedo/2"), std::string::npos) << e.info().path;
  }
  EXPECT_EQ(doc.get_component(ball, "core.DebugShape"), before);  // not even the first two elements
  EXPECT_FALSE(doc.history().can_undo());
}

TEST_F(Document, ASliderDragIsOneUndoStep) {
  EntityId sun = doc.find_by_name("sun");
  json original = doc.get_field(sun, "core.DirectionalLight", "elevation_deg");
  for (int i = 1; i <= 20; ++i) doc.set_field(sun, "core.DirectionalLight", "elevation_deg", 30 + i, true);
  doc.end_continuous_edit();  // IsItemDeactivatedAfterEdit
  EXPECT_EQ(doc.history().steps().size(), 1u);
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), json(50));
  doc.undo();
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), original);
  EXPECT_FALSE(doc.history().can_undo());
}

TEST_F(Document, SettingTheSameValueRecordsNothing) {
  EntityId sun = doc.find_by_name("sun");
  doc.set_field(sun, "core.DirectionalLight", "elevation_deg", doc.get_field(sun, "core.DirectionalLight", "elevation_deg"));
  EXPECT_FALSE(doc.history().can_undo());
}

TEST_F(Document, RemovedEntityComesBackWithItsIdAndEveryComponent) {
  EntityId ball = doc.find_by_name("ball");
  json shape = doc.get_component(ball, "core.DebugShape");
  doc.select(ball);
  doc.set_field(ball, "core.DebugShape", "size_m/0", 3.0);
  doc.remove_entity(ball);
  EXPECT_TRUE(doc.entity(ball).is_null());
  EXPECT_EQ(doc.selected(), kNoEntity);
  EXPECT_EQ(doc.entities().size(), 4u);
  doc.undo();  // the removal
  EXPECT_FALSE(doc.entity(ball).is_null());
  EXPECT_EQ(doc.display_name(ball), "ball");
  EXPECT_EQ(doc.selected(), ball);
  doc.undo();  // the size edit, addressed by the same id on the re-created entity
  EXPECT_EQ(doc.get_component(ball, "core.DebugShape"), shape);
  doc.redo();
  doc.redo();
  EXPECT_TRUE(doc.entity(ball).is_null());
}

TEST_F(Document, AddEntityAndComponentsAreUndoable) {
  EntityId e = doc.add_entity("cloud deck");
  EXPECT_EQ(doc.selected(), e);
  doc.add_component(e, "test.Clouds");  // loads the module that provides it
  EXPECT_TRUE(doc.world().modules().is_loaded("test"));
  EXPECT_EQ(doc.get_field(e, "test.Clouds", "layers/0/octaves"), json(4));
  doc.set_field(e, "test.Clouds", "mode", "precise");
  EXPECT_THROW(doc.add_component(e, "test.Clouds"), Error);
  doc.remove_component(e, "test.Clouds");
  EXPECT_TRUE(doc.get_component(e, "test.Clouds").is_null());
  doc.undo();
  EXPECT_EQ(doc.get_field(e, "test.Clouds", "mode"), json("precise"));
  doc.undo();
  doc.undo();
  EXPECT_TRUE(doc.get_component(e, "test.Clouds").is_null());
  doc.undo();
  EXPECT_TRUE(doc.entity(e).is_null());
  EXPECT_FALSE(doc.undo());
  for (int i = 0; i < 3; ++i) doc.redo();  // entity, component, mode; not the removal
  EXPECT_EQ(doc.get_field(e, "test.Clouds", "mode"), json("precise"));
  EXPECT_EQ(doc.display_name(e), "cloud deck");
}

TEST_F(Document, RenameGoesThroughTheNameComponent) {
  EntityId crate = doc.find_by_name("crate");
  doc.rename_entity(crate, "big crate");
  EXPECT_EQ(doc.find_by_name("big crate"), crate);
  doc.undo();
  EXPECT_EQ(doc.display_name(crate), "crate");
}

TEST_F(Document, EntityWithPrefersTheSelection) {
  EntityId ball = doc.find_by_name("ball"), crate = doc.find_by_name("crate");
  EXPECT_EQ(doc.entity_with("core.DebugShape"), ball);  // first in the file
  doc.select(crate);
  EXPECT_EQ(doc.entity_with("core.DebugShape"), crate);
  doc.select(doc.find_by_name("camera"));
  EXPECT_EQ(doc.entity_with("core.DebugShape"), ball);
}

TEST_F(Document, ABadSceneLeavesTheOpenSceneAlone) {
  ScratchDir dir("bad-scene");
  auto bad = dir.write("bad.json", R"({"welkin_scene": 1, "entities": [{"components": {"core.Camera": {"ev100": "bright"}}}]})");
  uint64_t generation = doc.world_generation();
  EXPECT_THROW(doc.load_scene(bad.string()), Error);
  EXPECT_EQ(doc.world_generation(), generation);
  EXPECT_EQ(doc.entities().size(), 5u);
  EXPECT_EQ(doc.scene_path(), kDebugScene);
}

TEST_F(Document, SavedSceneReloadsWithTheEdit) {
  ScratchDir dir("save-scene");
  doc.set_field(doc.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg", 123.5);
  std::string path = (dir.path() / "edited.json").string();
  doc.save_scene(path);
  EXPECT_FALSE(doc.dirty());
  EditorDocument again(editor_test::make_test_world);
  again.load_scene(path);
  EXPECT_EQ(again.get_field(again.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg"), json(123.5));
}

TEST_F(Document, LoadingASceneClearsTheHistoryAndBumpsTheGeneration) {
  doc.set_field(doc.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg", 10);
  uint64_t generation = doc.world_generation();
  doc.load_scene(kDebugScene);
  EXPECT_GT(doc.world_generation(), generation);
  EXPECT_FALSE(doc.history().can_undo());
}

}  // namespace
