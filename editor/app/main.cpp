// welkin-editor [SCENE] [--script FILE] [--size WxH] [--config FILE] [--no-config]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <regex>

#include "app/editor_app.h"
#include "model/script.h"

int main(int argc, char** argv) {
  welkin::editor::EditorOptions options;
  std::string size;
  CLI::App app("Welkin editor: tune presets on a live view, script time of day");
  app.add_option("scene", options.scene, "Scene file to open (JSON); default: the last scene opened");
  app.add_option("--script", options.script, "Run editor commands from FILE, one per frame (see --script-help)")
      ->check(CLI::ExistingFile);
  app.add_option("--size", size, "Window size WxH (default: as last time, else 1600x900)");
  app.add_option("--config", options.config, "Editor state file (default: $XDG_CONFIG_HOME/welkin/editor.json)");
  app.add_flag("--no-config", options.no_config, "Do not read or write the editor state file");
  bool script_help = false;
  app.add_flag("--script-help", script_help, "List the script commands and exit");
  CLI11_PARSE(app, argc, argv);
  if (script_help) {
    std::fputs(welkin::editor::script_verbs_help(), stdout);
    return 0;
  }
  if (!size.empty()) {
    std::smatch m;
    static const std::regex re(R"((\d{3,5})x(\d{3,5}))");
    if (!std::regex_match(size, m, re)) {
      std::fprintf(stderr, "welkin-editor: --size expects WIDTHxHEIGHT, e.g. 1600x900, found '%s'\n", size.c_str());
      return 2;
    }
    options.width = std::stoi(m[1]);
    options.height = std::stoi(m[2]);
  }
  return welkin::editor::run_editor(options);
}
