#include "model/command_history.h"

namespace welkin::editor {

DocumentPart part_of(EditTarget target) {
  // Painted maps are written with the scene, so they belong to it.
  return target == EditTarget::sequence ? DocumentPart::sequence : DocumentPart::scene;
}

void CommandHistory::record(Edit edit, std::string label, bool continuous) {
  steps_.resize(cursor_);  // a new edit forgets what could have been redone
  if (continuous) {
    if (Edit* open = open_edit(edit)) {
      open->after = std::move(edit.after);  // keep the value from before the drag began
      return;
    }
  }
  seal();
  // A merged edit stays in its step, so the step's versions stay right: it touches the same slot.
  std::array<PartVersion, kDocumentParts> versions{version(DocumentPart::scene), version(DocumentPart::sequence)};
  versions[size_t(part_of(edit.target))] = fresh_version();
  steps_.push_back(HistoryStep{.label = std::move(label), .edits = {std::move(edit)}, .open = continuous, .versions = versions});
  cursor_ = steps_.size();
  trim();
}

namespace {
size_t map_bytes(const HistoryStep& step) {
  size_t n = 0;
  for (const Edit& e : step.edits)
    if (e.target == EditTarget::map)
      for (const nlohmann::json* v : {&e.before, &e.after})
        if (v->is_object() && v->contains("texels") && (*v)["texels"].is_binary()) n += (*v)["texels"].get_binary().size();
  return n;
}
}  // namespace

void CommandHistory::trim() {
  size_t bytes = 0;
  for (const HistoryStep& s : steps_) bytes += map_bytes(s);
  size_t drop = 0;
  while (steps_.size() - drop > 1 && (steps_.size() - drop > kMaxSteps || bytes > kMaxMapBytes)) bytes -= map_bytes(steps_[drop++]);
  if (drop == 0) return;
  base_versions_ = steps_[drop - 1].versions;
  steps_.erase(steps_.begin(), steps_.begin() + long(drop));
  cursor_ = cursor_ > drop ? cursor_ - drop : 0;
}

Edit* CommandHistory::open_edit(const Edit& like) {
  if (steps_.empty() || cursor_ != steps_.size()) return nullptr;
  HistoryStep& top = steps_.back();
  return top.open && top.edits.size() == 1 && top.edits[0].same_slot(like) ? &top.edits[0] : nullptr;
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
  for (PartVersion& v : base_versions_) v = fresh_version();
}

}  // namespace welkin::editor
