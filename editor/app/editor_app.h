#pragma once
// The welkin-editor application: a GLFW window, Dear ImGui, the engine's renderer over the
// document's world, the registered panels, an optional script, and the remembered editor state.
#include <string>

namespace welkin::editor {

struct EditorOptions {
  std::string scene;        // scene to open; empty: the last one (editor config), else an empty scene
  std::string script;       // --script FILE: commands to run, one per frame
  int width = 0, height = 0;  // window size; 0: remembered (default 1600x900)
  std::string config;       // editor state file; empty: $XDG_CONFIG_HOME/welkin/editor.json
  bool no_config = false;   // neither read nor write the editor state
};

// Exit codes as the `welkin` CLI: 0 ok, 1 failure (a script line failed), 2 usage / no display,
// 3 bad input (the scene does not load).
int run_editor(const EditorOptions& options);

}  // namespace welkin::editor
