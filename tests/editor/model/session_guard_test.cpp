// The session guard: what would drop unsaved work asks first, a failed save keeps the prompt,
// "save as" asks before replacing a file, and the autosave brings back a crashed session's edits.
#include "model/session_guard.h"

#include <gtest/gtest.h>

#include "model/script.h"
#include "test_module.h"
#include "welkin/core/error.h"
#include "welkin/scene/scene_file.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using welkin::editor::Keyframe;
using welkin::editor::Sequence;
using welkin::editor::load_sequence_file;
using welkin::editor::save_sequence_file;
using editor_test::ScratchDir;
using nlohmann::json;
namespace fs = std::filesystem;

const char* kDebugScene = WELKIN_SOURCE_DIR "/assets/scenes/debug.json";
const char* kElevation = "core.DirectionalLight/elevation_deg";

json azimuth_of(EditorDocument& doc) { return doc.get_field(doc.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg"); }

json azimuth_in_file(const std::string& path) {
  EditorDocument doc(editor_test::make_test_world);
  doc.load_scene(path);
  return azimuth_of(doc);
}

class Guard : public ::testing::Test {
 protected:
  Guard() : dir("guard"), doc(editor_test::make_test_world), guard(doc, Autosave(dir.path() / "autosave"), 30.0) {
    scene = (dir.path() / "scene.json").string();
    doc.load_scene(kDebugScene);
    doc.save_scene(scene);  // a scene of our own to save over
  }
  void set_azimuth(double deg) { doc.set_field(doc.find_by_name("sun"), "core.DirectionalLight", "azimuth_deg", deg); }
  void add_key(double t, double value) { doc.set_sequence(with_key(doc.sequence(), "sun", kElevation, t, value), "key"); }

  ScratchDir dir;
  EditorDocument doc;
  SessionGuard guard;
  std::string scene;
};

TEST_F(Guard, QuitWithNothingUnsavedQuitsAtOnce) {
  guard.request(GuardedAction::quit);
  EXPECT_FALSE(guard.prompt());
  EXPECT_TRUE(guard.quit_approved());
}

TEST_F(Guard, QuitWithUnsavedEditsAsksAndWaitsForTheAnswer) {
  set_azimuth(10);
  guard.request(GuardedAction::quit);
  ASSERT_TRUE(guard.prompt());
  EXPECT_EQ(guard.prompt()->kind, PromptKind::unsaved);
  EXPECT_TRUE(guard.prompt()->scene);
  EXPECT_FALSE(guard.prompt()->sequence);
  EXPECT_EQ(prompt_text(*guard.prompt()), "The scene has unsaved changes. Save before quitting?");
  EXPECT_FALSE(guard.quit_approved());
  EXPECT_THROW(guard.request(GuardedAction::new_scene), Error);  // one question at a time
}

TEST_F(Guard, CancelKeepsTheSessionAndItsEdits) {
  set_azimuth(10);
  guard.request(GuardedAction::quit);
  guard.answer(Answer::cancel);
  EXPECT_FALSE(guard.prompt());
  EXPECT_FALSE(guard.quit_approved());
  EXPECT_TRUE(doc.scene_dirty());
  EXPECT_EQ(azimuth_of(doc), json(10));
}

TEST_F(Guard, DiscardQuitsWithoutWriting) {
  const json saved = azimuth_in_file(scene);
  set_azimuth(10);
  guard.request(GuardedAction::quit);
  guard.answer(Answer::discard);
  EXPECT_TRUE(guard.quit_approved());
  EXPECT_EQ(azimuth_in_file(scene), saved);
}

TEST_F(Guard, SaveWritesTheSceneAndSequenceThenQuits) {
  const std::string seq = (dir.path() / "seq.json").string();
  doc.save_sequence(seq);
  set_azimuth(10);
  add_key(0, 4);
  guard.request(GuardedAction::quit);
  ASSERT_TRUE(guard.prompt());
  EXPECT_TRUE(guard.prompt()->scene && guard.prompt()->sequence);
  EXPECT_EQ(prompt_text(*guard.prompt()), "The scene and sequence have unsaved changes. Save before quitting?");
  guard.answer(Answer::save);
  EXPECT_TRUE(guard.quit_approved());
  EXPECT_EQ(azimuth_in_file(scene), json(10));
  EXPECT_EQ(load_sequence_file(seq).tracks.size(), 1u);
}

TEST_F(Guard, ASaveThatFailsKeepsThePromptAndTheEditorOpen) {
  set_azimuth(10);
  // The scene's folder becomes a file: writing there fails whoever runs the test (root included).
  const fs::path sub = dir.path() / "sub";
  fs::create_directories(sub);
  doc.save_scene((sub / "s.json").string());
  set_azimuth(20);
  fs::remove_all(sub);
  dir.write("sub", "not a folder");
  guard.request(GuardedAction::quit);
  guard.answer(Answer::save);
  ASSERT_TRUE(guard.prompt());
  EXPECT_FALSE(guard.prompt()->error.empty());
  EXPECT_FALSE(guard.quit_approved());
  EXPECT_TRUE(doc.scene_dirty());
  bool reported = false;
  for (const GuardMessage& m : guard.take_messages()) reported = reported || m.error;
  EXPECT_TRUE(reported);
  guard.answer(Answer::cancel);
  EXPECT_FALSE(guard.quit_approved());
}

TEST_F(Guard, SavingASceneThatNeverHadAFileFailsWithAHint) {
  doc.new_scene();
  doc.add_entity("thing");
  guard.request(GuardedAction::quit);
  guard.answer(Answer::save);
  ASSERT_TRUE(guard.prompt());
  EXPECT_NE(guard.prompt()->error.find("Save scene as"), std::string::npos) << guard.prompt()->error;
}

TEST_F(Guard, OpeningOrStartingASceneAsksOnlyAboutTheScene) {
  add_key(0, 4);  // an unsaved sequence survives a scene change: no question
  guard.request(GuardedAction::open_scene, scene);
  EXPECT_FALSE(guard.prompt());
  EXPECT_EQ(doc.scene_path(), scene);
  doc.add_entity("thing");
  guard.request(GuardedAction::new_scene);
  ASSERT_TRUE(guard.prompt());
  EXPECT_TRUE(guard.prompt()->scene);
  EXPECT_FALSE(guard.prompt()->sequence);
  guard.answer(Answer::cancel);
  EXPECT_EQ(doc.scene_path(), scene);
  EXPECT_EQ(doc.entities().size(), 6u);  // the new entity is still there
  guard.request(GuardedAction::open_scene, kDebugScene);
  guard.answer(Answer::discard);
  EXPECT_EQ(doc.scene_path(), kDebugScene);
  EXPECT_FALSE(doc.scene_dirty());
}

TEST_F(Guard, OpeningAnotherSequenceAsksAboutTheSequenceAndSaveWritesIt) {
  const std::string first = (dir.path() / "first.json").string(), second = (dir.path() / "second.json").string();
  save_sequence_file(second, with_key({}, "sun", kElevation, 0, 9));
  add_key(0, 4);
  doc.save_sequence(first);
  add_key(5, 6);
  set_azimuth(1);  // the scene is not asked about when only a sequence is opened
  guard.request(GuardedAction::open_sequence, second);
  ASSERT_TRUE(guard.prompt());
  EXPECT_FALSE(guard.prompt()->scene);
  EXPECT_TRUE(guard.prompt()->sequence);
  guard.answer(Answer::save);
  EXPECT_FALSE(guard.prompt());
  EXPECT_EQ(load_sequence_file(first).tracks[0].keys.size(), 2u);  // saved before it went
  EXPECT_EQ(doc.sequence_path(), second);
  EXPECT_FALSE(doc.sequence_dirty());
}

TEST_F(Guard, SaveAsOntoAnExistingFileAsks) {
  const std::string other = dir.write("other.json", "keep me").string();
  set_azimuth(10);
  guard.request(GuardedAction::save_scene_as, other);
  ASSERT_TRUE(guard.prompt());
  EXPECT_EQ(guard.prompt()->kind, PromptKind::overwrite);
  EXPECT_THROW(guard.answer(Answer::discard), Error);  // not an answer to this question
  guard.answer(Answer::cancel);
  EXPECT_EQ(editor_test::read_bytes(other), "keep me");
  EXPECT_TRUE(doc.scene_dirty());
  guard.request(GuardedAction::save_scene_as, other);
  guard.answer(Answer::overwrite);
  EXPECT_EQ(azimuth_in_file(other), json(10));
  EXPECT_EQ(doc.scene_path(), other);
  EXPECT_FALSE(doc.scene_dirty());
}

TEST_F(Guard, SaveAsToANewFileOrTheScenesOwnDoesNotAsk) {
  set_azimuth(10);
  guard.request(GuardedAction::save_scene_as, scene);
  EXPECT_FALSE(guard.prompt());
  guard.request(GuardedAction::save_scene_as, (dir.path() / "new.json").string());
  EXPECT_FALSE(guard.prompt());
  EXPECT_EQ(azimuth_in_file((dir.path() / "new.json").string()), json(10));
}

TEST_F(Guard, AutosaveWaitsForTheIntervalAndOnlyWhileUnsaved) {
  const fs::path meta = dir.path() / "autosave" / "meta.json";
  guard.tick(0);
  guard.tick(100);
  EXPECT_FALSE(fs::exists(meta));  // nothing unsaved, nothing written
  set_azimuth(10);
  guard.tick(110);
  guard.tick(139);
  EXPECT_FALSE(fs::exists(meta));  // the edit is 29 s old: not yet
  guard.tick(140);
  EXPECT_TRUE(fs::exists(meta));
  EXPECT_TRUE(fs::exists(dir.path() / "autosave" / "scene.json"));
  EXPECT_FALSE(fs::exists(dir.path() / "autosave" / "sequence.json"));  // the sequence is saved
  const std::string autosaved = (dir.path() / "autosave" / "scene.json").string();
  EXPECT_EQ(azimuth_in_file(autosaved), json(10));
  const auto written = fs::last_write_time(meta);
  guard.tick(200);  // nothing new since: not written again
  EXPECT_EQ(fs::last_write_time(meta), written);
  set_azimuth(11);
  guard.tick(210);
  guard.tick(239);
  EXPECT_EQ(azimuth_in_file(autosaved), json(10));
  guard.tick(240);  // a later edit is written an interval after it
  EXPECT_EQ(azimuth_in_file(autosaved), json(11));
  doc.save_scene(scene);
  guard.tick(201);  // nothing unsaved any more: the autosave goes at once
  EXPECT_FALSE(fs::exists(meta));
}

TEST_F(Guard, ACleanQuitRemovesTheAutosave) {
  set_azimuth(10);
  guard.autosave_now();
  ASSERT_TRUE(fs::exists(dir.path() / "autosave" / "meta.json"));
  guard.request(GuardedAction::quit);
  guard.answer(Answer::discard);
  EXPECT_FALSE(fs::exists(dir.path() / "autosave" / "meta.json"));
  EXPECT_FALSE(fs::exists(dir.path() / "autosave" / "scene.json"));
}

TEST_F(Guard, AfterACrashTheNextSessionRecoversTheEdits) {
  set_azimuth(42);
  add_key(0, 7);
  guard.autosave_now();
  // The crash: this session ends without a quit. The next one starts on the same files.
  EditorDocument next(editor_test::make_test_world);
  SessionGuard next_guard(next, Autosave(dir.path() / "autosave"));
  next_guard.offer_recovery();
  ASSERT_TRUE(next_guard.prompt());
  EXPECT_EQ(next_guard.prompt()->kind, PromptKind::recover);
  EXPECT_TRUE(next_guard.prompt()->scene && next_guard.prompt()->sequence);
  next_guard.tick(0);
  next_guard.tick(1000);  // an unanswered offer is never written over
  EXPECT_THROW(next_guard.answer(Answer::save), Error);
  next_guard.answer(Answer::recover);
  EXPECT_FALSE(next_guard.prompt());
  EXPECT_EQ(azimuth_of(next), json(42));
  EXPECT_EQ(next.scene_path(), scene);  // saving goes to the file the edits were made on
  EXPECT_TRUE(next.scene_dirty());
  EXPECT_TRUE(next.sequence_dirty());
  ASSERT_EQ(next.sequence().tracks.size(), 1u);
  EXPECT_EQ(next.sequence().tracks[0].keys[0], (Keyframe{0, 7}));
  next_guard.request(GuardedAction::quit);
  EXPECT_TRUE(next_guard.prompt());  // the recovered work is unsaved work
}

TEST_F(Guard, DiscardingTheRecoveryRemovesTheAutosave) {
  set_azimuth(42);
  guard.autosave_now();
  EditorDocument next(editor_test::make_test_world);
  SessionGuard next_guard(next, Autosave(dir.path() / "autosave"));
  next_guard.offer_recovery();
  ASSERT_TRUE(next_guard.prompt());
  next_guard.answer(Answer::discard);
  EXPECT_FALSE(next.dirty());
  EXPECT_FALSE(fs::exists(dir.path() / "autosave" / "meta.json"));
  SessionGuard third(next, Autosave(dir.path() / "autosave"));
  third.offer_recovery();
  EXPECT_FALSE(third.prompt());
}

TEST_F(Guard, ScriptVerbsRaiseCheckAndAnswerPrompts) {
  PresetLibrary presets(editor_test::make_test_world());
  auto run = [&](const std::string& text) {
    for (const ScriptLine& line : parse_script(text, "s"))
      if (!run_session_verb(guard, doc, line)) {
        std::string out;
        ASSERT_TRUE(run_document_verb(doc, presets, line, out)) << line.verb;
      }
  };
  run("set core.DirectionalLight/azimuth_deg 10\nexpect-dirty scene yes\nexpect-dirty sequence no\nquit\n"
      "expect-prompt unsaved scene\nanswer cancel\nexpect-prompt none\n");
  EXPECT_FALSE(guard.quit_approved());
  EXPECT_THROW(run("expect-dirty scene no\n"), Error);
  EXPECT_THROW(run("expect-prompt unsaved\n"), Error);
  EXPECT_THROW(run("answer cancel\n"), Error);  // nothing asks
  run("quit\n");
  EXPECT_THROW(run("expect-prompt unsaved sequence\n"), Error);  // it names the scene
  EXPECT_THROW(run("answer maybe\n"), Error);
  run("answer save\n");
  EXPECT_TRUE(guard.quit_approved());
  EXPECT_EQ(azimuth_in_file(scene), json(10));
  EXPECT_TRUE(verb_allowed_during_prompt("answer"));
  EXPECT_FALSE(verb_allowed_during_prompt("set"));
}

}  // namespace
