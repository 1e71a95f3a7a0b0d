// The history alone: recording, merging of continuous edits, sealing, the redo tail.
#include "model/command_history.h"

#include <gtest/gtest.h>

namespace {

using namespace welkin::editor;
using nlohmann::json;

Edit field_edit(const std::string& path, json before, json after) {
  return Edit{.target = EditTarget::field, .entity = 1, .component = "core.Camera", .path = path, .before = before, .after = after};
}

TEST(CommandHistory, ContinuousEditsOfOneSlotMergeIntoOneStepKeepingTheFirstBefore) {
  CommandHistory h;
  h.record(field_edit("ev100", 10, 11), "drag", true);
  h.record(field_edit("ev100", 11, 12), "drag", true);
  h.record(field_edit("ev100", 12, 13), "drag", true);
  h.seal();
  ASSERT_EQ(h.steps().size(), 1u);
  EXPECT_EQ(h.steps()[0].edits[0].before, json(10));
  EXPECT_EQ(h.steps()[0].edits[0].after, json(13));
  EXPECT_FALSE(h.steps()[0].open);
}

TEST(CommandHistory, TwoDragsOfTheSameFieldAreTwoSteps) {
  CommandHistory h;
  h.record(field_edit("ev100", 10, 11), "drag", true);
  h.seal();  // released
  h.record(field_edit("ev100", 11, 12), "drag", true);
  h.seal();
  EXPECT_EQ(h.steps().size(), 2u);
}

TEST(CommandHistory, ADragOfAnotherFieldStartsANewStep) {
  CommandHistory h;
  h.record(field_edit("ev100", 10, 11), "drag", true);
  h.record(field_edit("pitch_deg", 0, 5), "drag", true);
  EXPECT_EQ(h.steps().size(), 2u);
  EXPECT_FALSE(h.steps()[0].open);
}

TEST(CommandHistory, ADragThatEndsWhereItBeganLeavesNoStep) {
  CommandHistory h;
  h.record(field_edit("ev100", 10, 11), "drag", true);
  h.record(field_edit("ev100", 11, 10), "drag", true);
  h.seal();
  EXPECT_TRUE(h.steps().empty());
  EXPECT_FALSE(h.can_undo());
}

TEST(CommandHistory, RecordingAfterUndoDropsTheRedoTail) {
  CommandHistory h;
  h.record(field_edit("ev100", 1, 2), "a", false);
  h.record(field_edit("ev100", 2, 3), "b", false);
  h.moved_back();
  ASSERT_TRUE(h.can_redo());
  h.record(field_edit("ev100", 2, 9), "c", false);
  EXPECT_FALSE(h.can_redo());
  ASSERT_EQ(h.steps().size(), 2u);
  EXPECT_EQ(h.steps()[1].label, "c");
}

TEST(CommandHistory, KeepsAtMostMaxSteps) {
  CommandHistory h;
  for (size_t i = 0; i < CommandHistory::kMaxSteps + 10; ++i) h.record(field_edit("ev100", int(i), int(i) + 1), "s", false);
  EXPECT_EQ(h.steps().size(), CommandHistory::kMaxSteps);
  EXPECT_EQ(h.cursor(), CommandHistory::kMaxSteps);
  EXPECT_EQ(h.steps().front().edits[0].before, json(10));
}

// Versions: what the document compares with its saved point to tell dirty from clean.
TEST(CommandHistory, EachPartsVersionChangesOnlyWithItsOwnEdits) {
  CommandHistory h;
  const PartVersion scene0 = h.version(DocumentPart::scene), sequence0 = h.version(DocumentPart::sequence);
  h.record(field_edit("ev100", 10, 11), "set", false);
  EXPECT_NE(h.version(DocumentPart::scene), scene0);
  EXPECT_EQ(h.version(DocumentPart::sequence), sequence0);
  const PartVersion scene1 = h.version(DocumentPart::scene);
  h.record(Edit{.target = EditTarget::sequence, .before = json::object(), .after = json{{"k", 1}}}, "key", false);
  EXPECT_EQ(h.version(DocumentPart::scene), scene1);
  EXPECT_NE(h.version(DocumentPart::sequence), sequence0);
  h.moved_back();
  h.moved_back();
  EXPECT_EQ(h.version(DocumentPart::scene), scene0);  // undone: the same as before the edits
  EXPECT_EQ(h.version(DocumentPart::sequence), sequence0);
}

TEST(CommandHistory, TrimmingAndClearingNeverBringBackAnOldVersion) {
  CommandHistory h;
  const PartVersion start = h.version(DocumentPart::scene);
  for (size_t i = 0; i <= CommandHistory::kMaxSteps; ++i) h.record(field_edit("ev100", int(i), int(i) + 1), "set", false);
  ASSERT_EQ(h.steps().size(), CommandHistory::kMaxSteps);  // the first step was dropped
  while (h.can_undo()) h.moved_back();
  EXPECT_NE(h.version(DocumentPart::scene), start);  // still one edit past the start
  const PartVersion before_clear = h.version(DocumentPart::scene);
  h.clear();
  EXPECT_NE(h.version(DocumentPart::scene), before_clear);
  EXPECT_NE(h.version(DocumentPart::scene), start);
}

}  // namespace
