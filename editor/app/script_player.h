#pragma once
// Plays an editor script one line per frame, so every line's effect is rendered before the next
// (a screenshot after a `set` shows the change). Document verbs run in the model; the application
// handles the rest through `app_verb`.
#include <functional>
#include <string>
#include <vector>

#include "model/script.h"
#include "ui/editor_context.h"

namespace welkin::editor {

class ScriptPlayer {
 public:
  ScriptPlayer() = default;
  explicit ScriptPlayer(std::vector<ScriptLine> lines) : lines_(std::move(lines)) {}
  bool active() const { return next_ < lines_.size() || wait_frames_ > 0; }
  bool loaded() const { return !lines_.empty(); }
  // Runs the next line (or counts down a `wait`). `app_verb` returns false for a verb it does not
  // know. Throws Error naming file:line on failure.
  void step(EditorContext& ctx, const std::function<bool(const ScriptLine&)>& app_verb);

 private:
  std::vector<ScriptLine> lines_;
  size_t next_ = 0;
  int wait_frames_ = 0;
};

}  // namespace welkin::editor
