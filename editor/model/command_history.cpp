#include "model/command_history.h"

namespace welkin::editor {

void CommandHistory::record(Edit edit, std::string label, bool continuous) {
  steps_.resize(cursor_);  // a new edit forgets what could have been redone
  if (continuous && !steps_.empty()) {
    HistoryStep& top = steps_.back();
    if (top.open && top.edits.size() == 1 && top.edits[0].same_slot(edit)) {
      top.edits[0].after = std::move(edit.after);  // keep the value from before the drag began
      return;
    }
  }
  seal();
  steps_.push_back(HistoryStep{.label = std::move(label), .edits = {std::move(edit)}, .open = continuous});
  if (steps_.size() > kMaxSteps) steps_.erase(steps_.begin());
  cursor_ = steps_.size();
}

void CommandHistory::seal() {
  if (steps_.empty() || cursor_ != steps_.size() || !steps_.back().open) return;
  HistoryStep& top = steps_.back();
  top.open = false;
  bool changed = false;
  for (const Edit& e : top.edits) changed = changed || e.before != e.after;
  if (!changed) {
    steps_.pop_back();
    cursor_ = steps_.size();
  }
}

void CommandHistory::clear() {
  steps_.clear();
  cursor_ = 0;
}

}  // namespace welkin::editor
