#pragma once
// Panels a module registers as data, read without loading the module: <data_dir>/editor/panels.json
//
//   { "panels": [ { "title": "Time of day", "components": ["timeofday.TimeOfDay", "timeofday.SequencePlayer"] },
//                 { "title": "Weather map", "map": { "component": "clouds.VolumetricClouds",
//                                                    "file_field": "coverage_map", "size_field": "coverage_map_size_m" } } ] }
//
// A panel shows the listed components of the first entity that has each, through the reflection
// inspector, or a map painted over the planet (welkin/scene/painted_map.h) that a component names,
// with a brush; it appears while the scene has the module loaded. (Panels that draw more than fields
// need code in the module's editor part; see the report on runtime changes.)
#include <optional>
#include <string>
#include <vector>

#include "welkin/core/module.h"

namespace welkin::editor {

// A painted map a component names: the string field holding its file, the number giving its side (m).
struct MapFieldSpec {
  std::string component, file_field, size_field;
  friend bool operator==(const MapFieldSpec&, const MapFieldSpec&) = default;
};

struct ModulePanelSpec {
  std::string module;
  std::string title;
  std::vector<std::string> components;  // full names, each declared by `module`
  std::optional<MapFieldSpec> map;      // a map panel instead of fields
  friend bool operator==(const ModulePanelSpec&, const ModulePanelSpec&) = default;
};

// The panels every installed module declares. A module without the file declares none; a file that
// does not validate is skipped and its error (file and JSON path) added to `errors`.
std::vector<ModulePanelSpec> read_module_panels(const ModuleHost& modules, std::vector<std::string>& errors);

}  // namespace welkin::editor
