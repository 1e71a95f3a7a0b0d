#pragma once
// Panels a module registers as data, read without loading the module: <data_dir>/editor/panels.json
//
//   { "panels": [ { "title": "Time of day", "components": ["timeofday.TimeOfDay", "timeofday.SequencePlayer"] } ] }
//
// Each panel shows the listed components of the first entity that has each, through the reflection
// inspector, and appears while the scene has the module loaded. (Panels that draw more than fields
// need code in the module's editor part; see the report on runtime changes.)
#include <string>
#include <vector>

#include "welkin/core/module.h"

namespace welkin::editor {

struct ModulePanelSpec {
  std::string module;
  std::string title;
  std::vector<std::string> components;  // full names, each declared by `module`
  friend bool operator==(const ModulePanelSpec&, const ModulePanelSpec&) = default;
};

// The panels every installed module declares. A module without the file declares none; a file that
// does not validate is skipped and its error (file and JSON path) added to `errors`.
std::vector<ModulePanelSpec> read_module_panels(const ModuleHost& modules, std::vector<std::string>& errors);

}  // namespace welkin::editor
