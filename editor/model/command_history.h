#pragma once
// The undo/redo history: a list of steps (each one or more edits) and a cursor. The history only
// records; EditorDocument applies edits and asks the history which step to apply next.
#include <string>
#include <vector>

#include "model/edit.h"

namespace welkin::editor {

struct HistoryStep {
  std::string label;
  std::vector<Edit> edits;
  bool open = false;  // a continuous edit (slider drag) still merging into this step
};

class CommandHistory {
 public:
  // Records an edit that was just applied; drops the redo tail. A continuous edit merges into the
  // open step when that step edits the same slot, so a whole drag is one undo step.
  void record(Edit edit, std::string label, bool continuous);
  // The open step's edit when it is the only one and edits the same slot as `like` (a brush stroke
  // growing its rectangle); nullptr otherwise.
  Edit* open_edit(const Edit& like);
  // Closes the open step (the widget was released). A step whose net change is nothing is dropped.
  void seal();

  bool can_undo() const { return cursor_ > 0; }
  bool can_redo() const { return cursor_ < steps_.size(); }
  // The step undo or redo would apply; nullptr when there is none.
  const HistoryStep* next_undo() const { return can_undo() ? &steps_[cursor_ - 1] : nullptr; }
  const HistoryStep* next_redo() const { return can_redo() ? &steps_[cursor_] : nullptr; }
  // Move the cursor once the caller has applied next_undo() / next_redo().
  void moved_back() { --cursor_; }
  void moved_forward() { ++cursor_; }

  const std::vector<HistoryStep>& steps() const { return steps_; }
  size_t cursor() const { return cursor_; }
  void clear();

  // Oldest steps are dropped beyond this many (each holds JSON copies of the values it touched),
  // or while the texels painted maps' steps hold exceed kMaxMapBytes (the newest step always stays).
  static constexpr size_t kMaxSteps = 1000;
  static constexpr size_t kMaxMapBytes = size_t(256) << 20;
  void trim();

 private:
  std::vector<HistoryStep> steps_;
  size_t cursor_ = 0;  // steps_[0, cursor_) are done; the rest can be redone
};

}  // namespace welkin::editor
