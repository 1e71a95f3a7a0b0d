#pragma once
// Editor scripts (`welkin-editor --script FILE`): one command per line, run in order, one per
// frame, so a session can be replayed under Xvfb and its results checked. Parsing and every verb
// that needs only the document live here (tested without a window); the application adds the
// verbs that need the viewport (screenshot, view, wait, quit).
#include <string>
#include <vector>

#include "model/editor_document.h"
#include "model/preset_library.h"
#include "model/session_guard.h"

namespace welkin::editor {

struct ScriptLine {
  std::string file;
  int number = 0;
  std::string verb;
  std::vector<std::string> args;
  std::string text;                // the line after variable expansion
  std::vector<size_t> arg_offsets;  // where each argument starts in `text`

  // The raw text from argument i to the end of the line (JSON values may contain spaces).
  std::string tail(size_t i) const;
  // "file:line", for messages.
  std::string where() const { return file + ":" + std::to_string(number); }
};

// '#' starts a comment, blank lines are skipped, "double quotes" keep spaces in one argument (\" and
// \\ escape), and $NAME / ${NAME} are replaced from the environment ($$ is a dollar). Throws Error
// naming file:line for an unterminated quote or an unset variable.
std::vector<ScriptLine> parse_script(const std::string& text, const std::string& file);
std::vector<ScriptLine> load_script(const std::string& path);

// Runs a verb that needs only the document and the presets; appends anything it prints to
// `output`. Returns false when the verb is not one of these. Throws Error on failure.
bool run_document_verb(EditorDocument& doc, PresetLibrary& presets, const ScriptLine& line, std::string& output);

// Runs a verb that goes through the session guard: the actions that may drop or overwrite work
// (quit, new-scene, load-scene, load-sequence, save-scene; they raise its prompts) and the verbs
// that answer and check them (answer, expect-prompt, expect-dirty, autosave-now). Returns false for
// any other verb. Throws Error on failure. Shadows run_document_verb's verbs of the same names.
bool run_session_verb(SessionGuard& guard, EditorDocument& doc, const ScriptLine& line);
// While a prompt waits, a script may only answer or check it (or wait, or take screenshots).
bool verb_allowed_during_prompt(const std::string& verb);

// One line per verb, for --help and error messages.
const char* script_verbs_help();

}  // namespace welkin::editor
