#pragma once
// Keeps the editor from losing work. Quitting, opening or starting a scene, and opening another
// sequence ask first when they would drop unsaved edits (naming the scene, the sequence or both);
// "save as" asks before replacing another file; the autosave (model/autosave.h) is written every
// so often and offered back at start. The prompts are plain state here, answered by the ImGui
// modal or by a script's `answer` line, so scripted sessions and tests drive them the same way.
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "model/autosave.h"
#include "model/editor_document.h"

namespace welkin::editor {

// What the user asked for that may drop or overwrite work.
enum class GuardedAction { quit, new_scene, open_scene, open_sequence, save_scene_as, recover };

enum class PromptKind {
  unsaved,    // Save / Discard / Cancel: the action would drop unsaved edits
  overwrite,  // Overwrite / Cancel: "save as" names another file that exists
  recover,    // Recover / Discard: an autosave from a session that did not end cleanly
};

enum class Answer { save, discard, cancel, overwrite, recover };

struct Prompt {
  PromptKind kind = PromptKind::unsaved;
  GuardedAction action = GuardedAction::quit;
  std::string path;                      // the file to open or save as
  bool scene = false, sequence = false;  // the parts unsaved (unsaved) or autosaved (recover)
  std::string error;                     // why the last answer failed (a save); the prompt stays
};

// "scene", "sequence" or "scene and sequence".
std::string describe_parts(bool scene, bool sequence);
// The prompt's question, e.g. "The scene and sequence have unsaved changes. Save before quitting?"
std::string prompt_text(const Prompt& prompt);
const char* prompt_kind_name(PromptKind kind);  // "unsaved", "overwrite", "recover"
std::optional<PromptKind> prompt_kind_named(const std::string& name);
std::optional<Answer> answer_named(const std::string& name);  // "save", "discard", ...

struct GuardMessage {
  bool error = false;
  std::string text;
};

class SessionGuard {
 public:
  static constexpr double kDefaultAutosaveInterval_s = 30.0;
  SessionGuard(EditorDocument& doc, Autosave autosave, double autosave_interval_s = kDefaultAutosaveInterval_s);

  // Does the action now when nothing would be lost, else raises a prompt. Throws Error when the
  // action itself fails (the file does not load) or another prompt is still waiting.
  void request(GuardedAction action, const std::string& path = {});
  // At start: raises the recover prompt when an autosave is left from an earlier session.
  void offer_recovery();

  const std::optional<Prompt>& prompt() const { return prompt_; }
  // Carries out the answer. Throws Error when it does not fit the prompt (answer recover to an
  // unsaved prompt) or the action then fails; a save that fails keeps the prompt, with the error.
  void answer(Answer answer);
  // The quit prompt was answered (or nothing was unsaved): the application may close.
  bool quit_approved() const { return quit_approved_; }

  // Writes the autosave once the document has held unsaved edits the autosave lacks for
  // `interval`; removes it once nothing is unsaved. `now_s` is any steady clock in seconds.
  void tick(double now_s);
  void autosave_now();  // at once, whatever the time (script `autosave-now`); throws Error
  Autosave& autosave() { return autosave_; }

  // Messages for the log since the last call ("saved …", errors of autosave writes).
  std::vector<GuardMessage> take_messages() { return std::exchange(messages_, {}); }

 private:
  void perform(GuardedAction action, const std::string& path);
  // Saves the parts the prompt names to their files; false (and prompt_->error) when one fails.
  bool save_unsaved_parts();
  void write_autosave();

  EditorDocument& doc_;
  Autosave autosave_;
  double autosave_interval_s_;
  std::optional<double> behind_since_s_;  // when the autosave first lacked the document's edits
  std::optional<AutosaveContents> recoverable_;
  std::optional<Prompt> prompt_;
  bool quit_approved_ = false;
  std::vector<GuardMessage> messages_;
};

}  // namespace welkin::editor
