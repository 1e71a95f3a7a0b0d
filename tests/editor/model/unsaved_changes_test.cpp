// Whether the scene and the sequence are saved follows the undo position, each on its own: undoing
// back to the saved point is clean again, a new edit after it is not.
#include <gtest/gtest.h>

#include "model/editor_document.h"
#include "test_module.h"
#include "welkin/scene/scene_file.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using welkin::editor::Keyframe;
using welkin::editor::Sequence;
using welkin::editor::load_sequence_file;
using welkin::editor::save_sequence_file;
using editor_test::ScratchDir;

const char* kDebugScene = WELKIN_SOURCE_DIR "/assets/scenes/debug.json";
const char* kElevation = "core.DirectionalLight/elevation_deg";

class Unsaved : public ::testing::Test {
 protected:
  Unsaved() : doc(editor_test::make_test_world) { doc.load_scene(kDebugScene); }
  void set_azimuth(double deg) { doc.set_field(doc.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg", deg); }
  void add_key(double t, double value) { doc.set_sequence(with_key(doc.sequence(), "sun", kElevation, t, value), "key"); }
  EditorDocument doc;
};

TEST_F(Unsaved, UndoBackToTheLoadedSceneIsCleanAgain) {
  EXPECT_FALSE(doc.dirty());
  set_azimuth(10);
  EXPECT_TRUE(doc.dirty());
  doc.undo();
  EXPECT_FALSE(doc.dirty());  // the scene is what the file holds again
  doc.redo();
  EXPECT_TRUE(doc.dirty());
}

TEST_F(Unsaved, UndoBackToTheSavedPointIsCleanAndBeyondItIsDirty) {
  ScratchDir dir("unsaved-saved-point");
  set_azimuth(10);
  set_azimuth(20);
  doc.save_scene((dir.path() / "s.json").string());
  EXPECT_FALSE(doc.dirty());
  doc.undo();  // 10: not what the file holds
  EXPECT_TRUE(doc.dirty());
  doc.redo();
  EXPECT_FALSE(doc.dirty());
  doc.undo();
  doc.undo();  // as loaded: still not the saved file
  EXPECT_TRUE(doc.dirty());
}

TEST_F(Unsaved, ANewEditAfterUndoingToTheSavedPointIsDirtyEvenWhenUndone) {
  ScratchDir dir("unsaved-new-branch");
  set_azimuth(10);
  doc.save_scene((dir.path() / "s.json").string());
  doc.undo();
  set_azimuth(30);  // drops the saved step from the redo tail
  EXPECT_TRUE(doc.dirty());
  EXPECT_FALSE(doc.redo());
  doc.undo();  // back at the loaded scene, which is not what was saved
  EXPECT_TRUE(doc.dirty());
}

TEST_F(Unsaved, TheSequenceIsTrackedApartFromTheScene) {
  ScratchDir dir("unsaved-sequence");
  add_key(0, 5);
  EXPECT_TRUE(doc.sequence_dirty());
  EXPECT_FALSE(doc.scene_dirty());
  set_azimuth(10);
  EXPECT_TRUE(doc.scene_dirty());
  doc.save_scene((dir.path() / "scene.json").string());
  EXPECT_FALSE(doc.scene_dirty());
  EXPECT_TRUE(doc.sequence_dirty());  // saving the scene does not save the sequence
  doc.save_sequence((dir.path() / "seq.json").string());
  EXPECT_FALSE(doc.sequence_dirty());
  doc.undo();  // the azimuth: the scene differs from its file, the sequence still matches its own
  EXPECT_TRUE(doc.scene_dirty());
  EXPECT_FALSE(doc.sequence_dirty());
  doc.undo();  // the key
  EXPECT_TRUE(doc.sequence_dirty());
}

TEST_F(Unsaved, ALoadedSequenceIsCleanAndUndoingTheLoadIsNot) {
  ScratchDir dir("unsaved-load-sequence");
  const std::string path = (dir.path() / "s.json").string();
  save_sequence_file(path, with_key({}, "sun", kElevation, 0, 1));
  doc.load_sequence(path);
  EXPECT_FALSE(doc.sequence_dirty());
  doc.undo();
  EXPECT_TRUE(doc.sequence_dirty());
}

TEST_F(Unsaved, OpeningAnotherSceneKeepsAnUnsavedSequenceUnsaved) {
  add_key(0, 5);
  set_azimuth(10);
  doc.load_scene(kDebugScene);  // clears the history the key was in
  EXPECT_FALSE(doc.scene_dirty());
  EXPECT_TRUE(doc.sequence_dirty());
  doc.new_scene();
  EXPECT_TRUE(doc.sequence_dirty());
}

TEST_F(Unsaved, ADragStillMergingWhenSavedIsDirtyOnceItMovesOn) {
  ScratchDir dir("unsaved-drag");
  EntityId sun = doc.find_by_name("sun");
  doc.set_field(sun, "core.DirectionalLight", "azimuth_deg", 11, true);
  doc.save_scene((dir.path() / "s.json").string());
  EXPECT_FALSE(doc.dirty());
  doc.set_field(sun, "core.DirectionalLight", "azimuth_deg", 12, true);  // the same drag goes on
  doc.end_continuous_edit();
  EXPECT_TRUE(doc.dirty());
}

TEST_F(Unsaved, ADragThatEndsWhereItBeganLeavesTheSceneClean) {
  EntityId sun = doc.find_by_name("sun");
  const auto start = doc.get_field(sun, "core.DirectionalLight", "azimuth_deg");
  doc.set_field(sun, "core.DirectionalLight", "azimuth_deg", 11, true);
  doc.set_field(sun, "core.DirectionalLight", "azimuth_deg", start, true);
  doc.end_continuous_edit();
  EXPECT_FALSE(doc.dirty());
}

TEST_F(Unsaved, RecoveredPartsKeepTheirOriginalNamesAndAreDirty) {
  ScratchDir dir("unsaved-recover");
  set_azimuth(77);
  const std::string autosaved = (dir.path() / "autosave-scene.json").string();
  save_scene_file(doc.world(), autosaved);
  save_sequence_file((dir.path() / "autosave-seq.json").string(), with_key({}, "sun", kElevation, 0, 3));
  EditorDocument fresh(editor_test::make_test_world);
  fresh.recover_scene(autosaved, "/somewhere/original.json");
  fresh.recover_sequence((dir.path() / "autosave-seq.json").string(), "/somewhere/original-seq.json");
  EXPECT_EQ(fresh.scene_path(), "/somewhere/original.json");
  EXPECT_EQ(fresh.sequence_path(), "/somewhere/original-seq.json");
  EXPECT_TRUE(fresh.scene_dirty());
  EXPECT_TRUE(fresh.sequence_dirty());
  EXPECT_EQ(fresh.get_field(fresh.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg"), nlohmann::json(77));
  ASSERT_EQ(fresh.sequence().tracks.size(), 1u);
}

}  // namespace
