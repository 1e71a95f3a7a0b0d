#pragma once
// The preset files of every module: a preset is a JSON object of one component's fields in
// <module data_dir>/presets/*.json (fields it leaves out keep the declared defaults), or of one element
// of a component's array of structs (a cloud layer of a genus: clouds/presets/genera/*.json). Sub-folders
// are searched too; a preset's name is its path there ("genera/cumulus"). The library finds, reads and
// validates them and writes new ones atomically. A file that fails to load is kept with its error and
// is never written over: it may hold someone's unfinished work.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "welkin/core/error.h"
#include "welkin/core/world.h"

namespace welkin::editor {

struct PresetFile {
  std::string module;
  std::string name;    // the path in the module's preset folder without .json ("noon", "genera/cumulus")
  std::string folder;  // the sub-folder it is in ("" at the top, "genera")
  std::filesystem::path file;
  std::string component;          // whose fields these are, inferred from the keys; "" if unknown
  std::string element_field;      // "": a whole component; else the array of structs it is one element of
  nlohmann::json fields;          // the object as the file holds it
  std::optional<ErrorInfo> error;  // why it failed to load (names the file and the JSON path)
  bool ok() const { return !error.has_value(); }
  bool is_element() const { return !element_field.empty(); }
  // What applying it changes: "clouds.VolumetricClouds" or "clouds.VolumetricClouds/layers".
  std::string target() const { return is_element() ? component + "/" + element_field : component; }
};

struct PresetFolder {
  std::string module;
  std::filesystem::path dir;
};

class PresetLibrary {
 public:
  // `catalog` is a world used only to look component types up, so that browsing presets loads no
  // module into the scene being edited.
  explicit PresetLibrary(std::unique_ptr<World> catalog);

  // A folder searched besides each module's <data_dir>/presets (e.g. assets/presets/core for the
  // built-in module, which has no data folder).
  void add_folder(PresetFolder folder);
  // Every folder, the modules' own first, in module-name order.
  std::vector<PresetFolder> folders() const;
  // Re-reads every preset file, in sub-folders too (at most kMaxFolderDepth below a preset folder).
  void rescan();
  static constexpr int kMaxFolderDepth = 4;
  const std::vector<PresetFile>& presets() const { return presets_; }
  const PresetFile* find(std::string_view module, std::string_view name) const;
  std::vector<const PresetFile*> presets_for(std::string_view component) const;
  // The presets found in `folder`: those at its top first, then each sub-folder's, as the browser
  // lists them (sub-folders in name order, files in name order within each).
  std::vector<const PresetFile*> presets_in(const PresetFolder& folder) const;
  // Where new presets of `module` are saved: its first folder. Throws when it has none.
  std::filesystem::path folder_of(std::string_view module) const;

  // Reads one file as a preset of `module`, the component (or the element of a component's array of
  // structs) chosen among the module's components by the file's keys; on a tie a whole component.
  // `name` defaults to the file's stem. Errors are returned in PresetFile::error, never thrown.
  PresetFile read(const std::string& module, const std::filesystem::path& file, const std::string& name = "");
  // Reads one file as a preset of a given component.
  PresetFile read_for_component(const std::string& component, const std::filesystem::path& file);

  const TypeDesc& component_type(const std::string& component);
  // The type the preset's fields are of: its component's, or its array's element type.
  const TypeDesc& preset_type(const PresetFile& preset);
  // Every field of the preset's type: declared defaults overlaid with the file's fields.
  nlohmann::json complete_value(const PresetFile& preset);

  // Writes a component's value as a preset file (all fields, indented), through a temporary file
  // and a rename. Refuses to replace a file that exists but does not load as a preset of the same
  // component. Rescans afterwards.
  // (Arguments are copies: the rescan replaces the PresetFile a caller may have taken them from.)
  void save(std::string component, const nlohmann::json& value, std::filesystem::path file);
  // Writes one element of an array of structs over an element preset's own file (checked as above).
  void save_element(PresetFile preset, const nlohmann::json& element);
  // Renames a preset within its folder; refuses names with folders in them and existing targets.
  std::filesystem::path rename(PresetFile preset, const std::string& new_name);

 private:
  std::unique_ptr<World> catalog_;
  std::vector<PresetFolder> extra_folders_;
  std::vector<PresetFile> presets_;
};

}  // namespace welkin::editor
