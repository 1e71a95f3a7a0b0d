#include "model/session_guard.h"

#include <filesystem>

#include "welkin/core/error.h"

namespace welkin::editor {

namespace fs = std::filesystem;

namespace {

const char* action_words(GuardedAction a) {
  switch (a) {
    case GuardedAction::quit: return "quitting";
    case GuardedAction::new_scene: return "starting a new scene";
    case GuardedAction::open_scene: return "opening another scene";
    case GuardedAction::open_sequence: return "opening another sequence";
    case GuardedAction::save_scene_as: return "saving";
    case GuardedAction::recover: return "recovering";
  }
  return "";
}

// Whether `path` names the file the scene was loaded from or last saved to (then "save as" there
// replaces nothing the user did not mean to).
bool same_file(const std::string& path, const std::string& scene_path) {
  if (scene_path.empty()) return false;
  std::error_code ec;
  if (fs::equivalent(path, scene_path, ec)) return true;
  return fs::absolute(path, ec).lexically_normal() == fs::absolute(scene_path, ec).lexically_normal();
}

std::string error_text(const std::exception& e) {
  if (const auto* err = dynamic_cast<const Error*>(&e)) return format_error(err->info());
  return e.what();
}

}  // namespace

std::string describe_parts(bool scene, bool sequence) {
  if (scene && sequence) return "scene and sequence";
  return scene ? "scene" : sequence ? "sequence" : "nothing";
}

std::string prompt_text(const Prompt& p) {
  switch (p.kind) {
    case PromptKind::unsaved: {
      const bool both = p.scene && p.sequence;
      return "The " + describe_parts(p.scene, p.sequence) + (both ? " have" : " has") + " unsaved changes. Save before " +
             action_words(p.action) + "?";
    }
    case PromptKind::overwrite: return p.path + " already exists. Replace it?";
    case PromptKind::recover:
      return "The last session did not end cleanly. Its unsaved " + describe_parts(p.scene, p.sequence) +
             " can be recovered from the autosave.";
  }
  return "";
}

const char* prompt_kind_name(PromptKind kind) {
  switch (kind) {
    case PromptKind::unsaved: return "unsaved";
    case PromptKind::overwrite: return "overwrite";
    case PromptKind::recover: return "recover";
  }
  return "";
}

std::optional<PromptKind> prompt_kind_named(const std::string& name) {
  for (PromptKind k : {PromptKind::unsaved, PromptKind::overwrite, PromptKind::recover})
    if (name == prompt_kind_name(k)) return k;
  return std::nullopt;
}

std::optional<Answer> answer_named(const std::string& name) {
  if (name == "save") return Answer::save;
  if (name == "discard") return Answer::discard;
  if (name == "cancel") return Answer::cancel;
  if (name == "overwrite") return Answer::overwrite;
  if (name == "recover") return Answer::recover;
  return std::nullopt;
}

SessionGuard::SessionGuard(EditorDocument& doc, Autosave autosave, double autosave_interval_s)
    : doc_(doc), autosave_(std::move(autosave)), autosave_interval_s_(autosave_interval_s) {}

void SessionGuard::request(GuardedAction action, const std::string& path) {
  if (prompt_)
    throw Error(ErrorInfo{.message = std::string("a prompt is waiting (") + prompt_kind_name(prompt_->kind) + "): answer it first"});
  bool scene = false, sequence = false;
  switch (action) {
    case GuardedAction::quit: scene = doc_.scene_dirty(), sequence = doc_.sequence_dirty(); break;
    case GuardedAction::new_scene:
    case GuardedAction::open_scene: scene = doc_.scene_dirty(); break;
    case GuardedAction::open_sequence: sequence = doc_.sequence_dirty(); break;
    case GuardedAction::save_scene_as: {
      std::error_code ec;
      if (fs::exists(path, ec) && !same_file(path, doc_.scene_path())) {
        prompt_ = Prompt{.kind = PromptKind::overwrite, .action = action, .path = path};
        return;
      }
      break;
    }
    case GuardedAction::recover: throw Error(ErrorInfo{.message = "recovery is offered at start, not requested"});
  }
  if (scene || sequence) {
    prompt_ = Prompt{.kind = PromptKind::unsaved, .action = action, .path = path, .scene = scene, .sequence = sequence};
    return;
  }
  perform(action, path);
}

void SessionGuard::offer_recovery() {
  try {
    recoverable_ = autosave_.find();
  } catch (const std::exception& e) {
    messages_.push_back({true, "autosave not offered: " + error_text(e)});
    return;
  }
  if (recoverable_ && !prompt_)
    prompt_ = Prompt{.kind = PromptKind::recover, .action = GuardedAction::recover, .scene = recoverable_->scene,
                     .sequence = recoverable_->sequence};
}

void SessionGuard::perform(GuardedAction action, const std::string& path) {
  switch (action) {
    case GuardedAction::quit:
      quit_approved_ = true;
      autosave_.remove();  // everything was saved or knowingly discarded
      return;
    case GuardedAction::new_scene:
      doc_.new_scene();
      messages_.push_back({false, "new scene"});
      return;
    case GuardedAction::open_scene:
      doc_.load_scene(path);
      messages_.push_back({false, "opened " + path});
      return;
    case GuardedAction::open_sequence:
      doc_.load_sequence(path);
      messages_.push_back({false, "opened sequence " + path});
      return;
    case GuardedAction::save_scene_as:
      doc_.save_scene(path);
      messages_.push_back({false, "saved " + path});
      return;
    case GuardedAction::recover: return;
  }
}

bool SessionGuard::save_unsaved_parts() {
  try {
    if (prompt_->scene) {
      if (doc_.scene_path().empty())
        throw Error(ErrorInfo{.message = "the scene was never saved: cancel, then use File > Save scene as"});
      doc_.save_scene(doc_.scene_path());
      messages_.push_back({false, "saved " + doc_.scene_path()});
    }
    if (prompt_->sequence) {
      if (doc_.sequence_path().empty())
        throw Error(ErrorInfo{.message = "the sequence has no file: cancel, then save it from the timeline"});
      doc_.save_sequence(doc_.sequence_path());
      messages_.push_back({false, "saved " + doc_.sequence_path()});
    }
  } catch (const std::exception& e) {
    prompt_->error = error_text(e);
    messages_.push_back({true, prompt_->error});
    return false;
  }
  return true;
}

void SessionGuard::answer(Answer answer) {
  if (!prompt_) throw Error(ErrorInfo{.message = "no prompt is waiting for an answer"});
  const Prompt p = *prompt_;
  auto wrong = [&](const char* answers) {
    throw Error(ErrorInfo{.expected = answers, .message = std::string("the ") + prompt_kind_name(p.kind) + " prompt takes " + answers});
  };
  switch (p.kind) {
    case PromptKind::unsaved:
      if (answer == Answer::save) {
        if (!save_unsaved_parts()) return;  // the editor stays, the prompt shows why
      } else if (answer != Answer::discard && answer != Answer::cancel) {
        wrong("save, discard or cancel");
      }
      prompt_.reset();
      if (answer != Answer::cancel) perform(p.action, p.path);
      return;
    case PromptKind::overwrite:
      if (answer == Answer::cancel) {
        prompt_.reset();
      } else if (answer == Answer::overwrite) {
        try {
          doc_.save_scene(p.path);
        } catch (const std::exception& e) {
          prompt_->error = error_text(e);
          messages_.push_back({true, prompt_->error});
          return;
        }
        prompt_.reset();
        messages_.push_back({false, "saved " + p.path});
      } else {
        wrong("overwrite or cancel");
      }
      return;
    case PromptKind::recover:
      if (answer == Answer::discard) {
        autosave_.remove();
        recoverable_.reset();
        prompt_.reset();
      } else if (answer == Answer::recover) {
        try {
          autosave_.recover(doc_, *recoverable_);
        } catch (const std::exception& e) {
          prompt_->error = error_text(e);
          messages_.push_back({true, prompt_->error});
          return;
        }
        recoverable_.reset();
        prompt_.reset();
        messages_.push_back({false, "recovered the unsaved " + describe_parts(p.scene, p.sequence)});
      } else {
        wrong("recover or discard");
      }
      return;
  }
}

void SessionGuard::write_autosave() {
  behind_since_s_.reset();  // also after a failure: try again an interval later, not every frame
  try {
    autosave_.write(doc_);
  } catch (const std::exception& e) {
    messages_.push_back({true, "autosave failed: " + error_text(e)});
  }
}

void SessionGuard::tick(double now_s) {
  // Until the recover prompt is answered, the autosave on disk is the last session's: keep it.
  if (prompt_ && prompt_->kind == PromptKind::recover) return;
  if (!autosave_.behind(doc_)) {
    behind_since_s_.reset();
    return;
  }
  // A save that left nothing unsaved removes the autosave at once; edits wait an interval, so no
  // edit is older than that on disk and the disk is not written every frame of a drag.
  if (!behind_since_s_) behind_since_s_ = now_s;
  if (!doc_.dirty() || now_s - *behind_since_s_ >= autosave_interval_s_) write_autosave();
}

void SessionGuard::autosave_now() {
  if (prompt_ && prompt_->kind == PromptKind::recover)
    throw Error(ErrorInfo{.message = "the recover prompt is waiting: answer it before autosaving over that autosave"});
  if (!autosave_.enabled()) throw Error(ErrorInfo{.message = "autosave is off (no editor state folder, or --no-config)"});
  autosave_.write(doc_);
  behind_since_s_.reset();
}

}  // namespace welkin::editor
