#include "model/preset_library.h"

#include <algorithm>

#include "model/reflected_object.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A preset file and its name in its folder: the path below it without .json ("genera/cumulus").
struct FoundFile {
  fs::path file;
  std::string name, folder;
};

// The .json files in `dir` and its sub-folders (at most `depth` below), in name order; symbolic links
// to folders are not followed, so a loop of links cannot make the scan endless.
void json_files(const fs::path& dir, const std::string& folder, int depth, std::vector<FoundFile>& out) {
  std::error_code ec;
  std::vector<fs::directory_entry> entries;
  for (const auto& entry : fs::directory_iterator(dir, ec)) entries.push_back(entry);
  std::sort(entries.begin(), entries.end());
  const std::string prefix = folder.empty() ? "" : folder + "/";
  for (const auto& entry : entries) {
    const std::string leaf = entry.path().filename().string();
    if (entry.is_regular_file(ec) && entry.path().extension() == ".json")
      out.push_back(FoundFile{entry.path(), prefix + entry.path().stem().string(), folder});
    else if (depth > 0 && !leaf.starts_with(".") && entry.is_directory(ec) && !entry.is_symlink(ec))
      json_files(entry.path(), prefix + leaf, depth - 1, out);
  }
}

ErrorInfo located(const Error& err, const fs::path& file) {
  ErrorInfo info = err.info();
  if (info.file.empty()) info.file = file.string();
  return info;
}

size_t matching_keys(const TypeDesc& type, const json& fields) {
  size_t n = 0;
  for (auto it = fields.begin(); it != fields.end(); ++it) n += type.field(it.key()) ? 1 : 0;
  return n;
}

}  // namespace

PresetLibrary::PresetLibrary(std::unique_ptr<World> catalog) : catalog_(std::move(catalog)) {}

void PresetLibrary::add_folder(PresetFolder folder) { extra_folders_.push_back(std::move(folder)); }

std::vector<PresetFolder> PresetLibrary::folders() const {
  std::vector<PresetFolder> out;
  for (const ModuleManifest& m : catalog_->modules().available())
    if (!m.data_dir.empty()) out.push_back(PresetFolder{m.name, m.data_dir / "presets"});
  for (const PresetFolder& f : extra_folders_) out.push_back(f);
  std::stable_sort(out.begin(), out.end(), [](const PresetFolder& a, const PresetFolder& b) { return a.module < b.module; });
  return out;
}

void PresetLibrary::rescan() {
  presets_.clear();
  for (const PresetFolder& folder : folders()) {
    std::vector<FoundFile> found;
    json_files(folder.dir, "", kMaxFolderDepth, found);
    for (const FoundFile& f : found) presets_.push_back(read(folder.module, f.file, f.name));
  }
}

const PresetFile* PresetLibrary::find(std::string_view module, std::string_view name) const {
  for (const PresetFile& p : presets_)
    if (p.module == module && p.name == name) return &p;
  return nullptr;
}

std::vector<const PresetFile*> PresetLibrary::presets_for(std::string_view component) const {
  std::vector<const PresetFile*> out;
  for (const PresetFile& p : presets_)
    if (p.component == component) out.push_back(&p);
  return out;
}

std::vector<const PresetFile*> PresetLibrary::presets_in(const PresetFolder& folder) const {
  std::vector<const PresetFile*> out;
  for (const PresetFile& p : presets_)
    if (p.module == folder.module &&
        p.file.parent_path() == (p.folder.empty() ? folder.dir : folder.dir / p.folder))
      out.push_back(&p);
  std::stable_sort(out.begin(), out.end(),
                   [](const PresetFile* a, const PresetFile* b) { return a->folder < b->folder; });
  return out;
}

fs::path PresetLibrary::folder_of(std::string_view module) const {
  for (const PresetFolder& f : folders())
    if (f.module == module) return f.dir;
  throw Error(ErrorInfo{.message = "module '" + std::string(module) + "' has no preset folder"});
}

const TypeDesc& PresetLibrary::component_type(const std::string& component) {
  return *catalog_->modules().require_component(component).type;
}

PresetFile PresetLibrary::read(const std::string& module, const fs::path& file, const std::string& name) {
  PresetFile preset{.module = module, .name = name.empty() ? file.stem().string() : name, .file = file};
  if (const size_t slash = preset.name.rfind('/'); slash != std::string::npos)
    preset.folder = preset.name.substr(0, slash);
  try {
    json doc = read_json_file(file.string());
    if (!doc.is_object())
      throw Error(ErrorInfo{.file = file.string(), .path = "/", .expected = "an object of component fields", .found = describe_json(doc)});
    const ModuleManifest* manifest = catalog_->modules().manifest(module);
    if (!manifest) throw Error(ErrorInfo{.file = file.string(), .message = "module '" + module + "' is not installed"});
    // The component whose fields the keys name; on a tie the first declared. With no full match the
    // closest one is validated, so the error names the first unknown key. An element of a component's
    // array of structs (a cloud layer) is chosen only when it matches more keys than every component.
    const TypeDesc* best = nullptr;
    size_t best_keys = 0;
    for (const std::string& c : manifest->components) {
      if (c == Name::kTypeName) continue;
      const TypeDesc& type = component_type(c);
      size_t keys = matching_keys(type, doc);
      if (!best || keys > best_keys) best = &type, best_keys = keys;
    }
    if (!best) throw Error(ErrorInfo{.file = file.string(), .message = "module '" + module + "' has no components"});
    preset.component = best->name;
    const TypeDesc* best_element = nullptr;
    for (const std::string& c : manifest->components) {
      if (c == Name::kTypeName) continue;
      for (const FieldDesc& f : component_type(c).fields) {
        if (f.kind != FieldKind::array || !f.element) continue;
        size_t keys = matching_keys(*f.element, doc);
        if (keys > best_keys)
          best_element = f.element, best_keys = keys, preset.component = c, preset.element_field = f.name;
      }
    }
    complete_component_json(best_element ? *best_element : *best, doc);  // validates every value
    preset.fields = std::move(doc);
  } catch (const Error& err) {
    preset.error = located(err, file);
  }
  return preset;
}

PresetFile PresetLibrary::read_for_component(const std::string& component, const fs::path& file) {
  PresetFile preset{.name = file.stem().string(), .file = file, .component = component};
  try {
    const ComponentInfo& info = catalog_->modules().require_component(component);
    preset.module = info.module;
    json doc = read_json_file(file.string());
    complete_component_json(*info.type, doc);
    preset.fields = std::move(doc);
  } catch (const Error& err) {
    preset.error = located(err, file);
  }
  return preset;
}

const TypeDesc& PresetLibrary::preset_type(const PresetFile& preset) {
  const TypeDesc& type = component_type(preset.component);
  if (!preset.is_element()) return type;
  const FieldDesc* f = type.field(preset.element_field);
  if (!f || f->kind != FieldKind::array || !f->element)
    throw Error(
        ErrorInfo{.file = preset.file.string(), .message = preset.target() + " is not an array of structs"});
  return *f->element;
}

json PresetLibrary::complete_value(const PresetFile& preset) {
  if (!preset.ok()) throw Error(*preset.error);
  return complete_component_json(preset_type(preset), preset.fields);
}

void PresetLibrary::save(std::string component, const json& value, fs::path file) {
  json complete = complete_component_json(component_type(component), value);
  std::error_code ec;
  if (fs::exists(file, ec)) {
    PresetFile existing = read_for_component(component, file);
    if (!existing.ok())
      throw Error(ErrorInfo{.file = file.string(),
                            .message = "exists but does not load as a " + component + " preset (" +
                                       format_error(*existing.error) + "); it was left untouched"});
  }
  if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
  write_file_atomically(file.string(), in_declaration_order(component_type(component), complete).dump(2) + "\n");
  rescan();
}

void PresetLibrary::save_element(PresetFile preset, const json& element) {
  if (!preset.is_element())
    throw Error(ErrorInfo{.file = preset.file.string(), .message = "not a preset of an array's element"});
  const TypeDesc& type = preset_type(preset);
  json complete = complete_component_json(type, element);
  PresetFile existing = read(preset.module, preset.file, preset.name);
  if (!existing.ok() || existing.target() != preset.target())
    throw Error(ErrorInfo{.file = preset.file.string(),
                          .message = "does not load as a " + preset.target() + " preset" +
                                     (existing.ok() ? "" : " (" + format_error(*existing.error) + ")") +
                                     "; it was left untouched"});
  write_file_atomically(preset.file.string(), in_declaration_order(type, complete).dump(2) + "\n");
  rescan();
}

fs::path PresetLibrary::rename(PresetFile preset, const std::string& new_name) {
  bool plain = !new_name.empty() && new_name.size() <= 128 && new_name.front() != '.' &&
               new_name.find_first_of("/\\") == std::string::npos;
  if (!plain)
    throw Error(ErrorInfo{.file = preset.file.string(), .expected = "a plain file name (no folders, not starting with '.')",
                          .found = "'" + new_name + "'", .message = "cannot rename preset"});
  fs::path target = preset.file.parent_path() / (new_name + ".json");
  std::error_code ec;
  if (fs::exists(target, ec))
    throw Error(ErrorInfo{.file = target.string(), .message = "a preset of that name exists; nothing was renamed"});
  fs::rename(preset.file, target, ec);
  if (ec) throw Error(ErrorInfo{.file = preset.file.string(), .message = "cannot rename: " + ec.message()});
  rescan();
  return target;
}

}  // namespace welkin::editor
