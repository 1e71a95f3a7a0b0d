#pragma once
// The undo/redo history: a list of steps (each one or more edits) and a cursor. The history only
// records; EditorDocument applies edits and asks the history which step to apply next.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/edit.h"

namespace welkin::editor {

// The two parts of a document that are saved to different files: the scene (with its painted
// maps) and the timeline's sequence. Each is dirty or clean on its own.
enum class DocumentPart { scene = 0, sequence = 1 };
inline constexpr size_t kDocumentParts = 2;
DocumentPart part_of(EditTarget target);

// Names what a part holds after some step. Equal versions mean the same content; a version is
// never reused, so a new edit after undoing to a saved point is not mistaken for it.
using PartVersion = uint64_t;

struct HistoryStep {
  std::string label;
  std::vector<Edit> edits;
  bool open = false;  // a continuous edit (slider drag) still merging into this step
  std::array<PartVersion, kDocumentParts> versions{};  // each part's version once this step is done
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
  // Forgets every step. Each part gets a fresh version that no earlier one equals.
  void clear();

  // What `part` holds at the cursor. The document keeps the version it last saved or loaded and
  // compares: undoing back to that point makes the part clean again.
  PartVersion version(DocumentPart part) const {
    return cursor_ > 0 ? steps_[cursor_ - 1].versions[size_t(part)] : base_versions_[size_t(part)];
  }

  // Oldest steps are dropped beyond this many (each holds JSON copies of the values it touched),
  // or while the texels painted maps' steps hold exceed kMaxMapBytes (the newest step always stays).
  static constexpr size_t kMaxSteps = 1000;
  static constexpr size_t kMaxMapBytes = size_t(256) << 20;
  void trim();

 private:
  PartVersion fresh_version() { return ++last_version_; }

  std::vector<HistoryStep> steps_;
  size_t cursor_ = 0;  // steps_[0, cursor_) are done; the rest can be redone
  // Versions before steps_[0]: at the start, after clear(), or of the newest step trim() dropped.
  std::array<PartVersion, kDocumentParts> base_versions_{};
  PartVersion last_version_ = 0;
};

}  // namespace welkin::editor
