#include "app/script_player.h"

#include <cstdio>
#include <cstdlib>

#include "welkin/core/error.h"
#include "welkin/core/log.h"

namespace welkin::editor {

void ScriptPlayer::step(EditorContext& ctx, const std::function<bool(const ScriptLine&)>& app_verb) {
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  if (next_ >= lines_.size()) return;
  const ScriptLine& line = lines_[next_++];
  try {
    if (line.verb == "wait") {
      char* end = nullptr;
      long frames = line.args.size() == 1 ? std::strtol(line.args[0].c_str(), &end, 10) : -1;
      if (line.args.size() != 1 || *end != '\0' || frames < 0 || frames > 100000)
        throw Error(ErrorInfo{.message = "usage: wait FRAMES (0..100000)"});
      wait_frames_ = int(frames);
      return;
    }
    SessionGuard& session = ctx.session;
    if (session.prompt() && !verb_allowed_during_prompt(line.verb))
      throw Error(ErrorInfo{.message = "'" + prompt_text(*session.prompt()) + "' waits for an answer (answer, see --script-help) before '" +
                                       line.verb + "'"});
    if (line.verb == "time" && line.args.size() == 1) ctx.timeline.playhead_s = std::strtod(line.args[0].c_str(), nullptr);
    std::string output;
    bool known = run_session_verb(session, ctx.doc, line) || run_document_verb(ctx.doc, ctx.presets, line, output) || app_verb(line);
    if (!output.empty()) {
      std::fputs(output.c_str(), stdout);  // `print` and `diff-preset` answer on stdout, like the CLI
      std::fflush(stdout);
      if (output.back() == '\n') output.pop_back();
      ctx.log.info(output);
    }
    if (!known) throw Error(ErrorInfo{.message = "unknown verb '" + line.verb + "'\n" + script_verbs_help()});
    // A script ending on `quit` asked to close, and no later line can answer its prompt: it
    // quits without saving, saying so (a script that wants its edits kept saves or answers).
    if (next_ == lines_.size() && line.verb == "quit" && session.prompt() && session.prompt()->kind == PromptKind::unsaved) {
      const std::string note = line.where() + ": the script ends at '" + prompt_text(*session.prompt()) + "': quitting without saving";
      log::warn(note);  // on stderr whatever the log level: edits were dropped
      ctx.log.info(note);
      session.answer(Answer::discard);
    }
  } catch (const Error& e) {
    ErrorInfo info = e.info();
    if (info.file.empty()) info.file = line.where();
    else if (info.file != line.where()) info.message = "(" + line.where() + ") " + info.message;
    throw Error(info);
  }
}

}  // namespace welkin::editor
