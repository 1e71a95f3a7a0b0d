#include <dlfcn.h>

#include <algorithm>
#include <unordered_set>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/core/log.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/scene/json_fields.h"

namespace welkin {

using nlohmann::json;

namespace {

std::string json_type(const json& j) { return j.type_name(); }

std::string read_string(const json& j, const char* key, const std::string& origin, bool required) {
  auto it = j.find(key);
  if (it == j.end()) {
    if (!required) return {};
    throw Error(
        ErrorInfo{.file = origin, .path = std::string("/") + key, .expected = "string", .found = "nothing"});
  }
  if (!it->is_string())
    throw Error(ErrorInfo{
        .file = origin, .path = std::string("/") + key, .expected = "string", .found = json_type(*it)});
  return it->get<std::string>();
}

std::vector<std::string> read_strings(const json& j, const char* key, const std::string& origin) {
  std::vector<std::string> out;
  auto it = j.find(key);
  if (it == j.end()) return out;
  if (!it->is_array())
    throw Error(ErrorInfo{.file = origin,
                          .path = std::string("/") + key,
                          .expected = "array of strings",
                          .found = json_type(*it)});
  for (size_t i = 0; i < it->size(); ++i) {
    if (!(*it)[i].is_string())
      throw Error(ErrorInfo{.file = origin, .path = std::string("/") + key + "/" + std::to_string(i),
                            .expected = "string", .found = json_type((*it)[i])});
    out.push_back((*it)[i].get<std::string>());
  }
  return out;
}

}  // namespace

ModuleManifest parse_module_manifest(const std::string& text, const std::string& origin) {
  const json j = parse_json_text(text, origin);  // bounded in size and depth, duplicate keys refused
  if (!j.is_object())
    throw Error(ErrorInfo{.file = origin, .path = "/", .expected = "object", .found = json_type(j)});
  ModuleManifest m;
  m.origin = origin;
  m.name = read_string(j, "name", origin, true);
  m.version = read_string(j, "version", origin, true);
  m.description = read_string(j, "description", origin, false);
  m.depends = read_strings(j, "depends", origin);
  m.uses = read_strings(j, "uses", origin);
  m.components = read_strings(j, "components", origin);
  m.library = read_string(j, "library", origin, false);
  m.data_dir = read_string(j, "data_dir", origin, false);
  // The library is a file beside the manifest: a path could make a dropped-in manifest load any
  // library on the machine (or, with no slash, whatever the loader's search finds).
  const std::string lib = m.library.string();
  if (!m.library.empty() && (lib.find_first_of("/\\") != std::string::npos || lib == "." || lib == ".."))
    throw Error(ErrorInfo{.file = origin,
                          .path = "/library",
                          .expected = "a file name beside the manifest (no folders)",
                          .found = "'" + lib + "'"});
  const std::string prefix = m.name + ".";  // once: a name and a list may both be long
  // Each other module is named once, in one of the two lists; never the module itself.
  std::unordered_set<std::string> named;
  for (const auto* list : {&m.depends, &m.uses})
    for (const auto& d : *list)
      if (d == m.name || !named.insert(d).second)
        throw Error(ErrorInfo{.file = origin, .path = list == &m.depends ? "/depends" : "/uses",
                              .expected = "other modules, each named once", .found = "'" + d + "'"});
  for (const auto& c : m.components)
    if (!c.starts_with(prefix))
      throw Error(ErrorInfo{.file = origin,
                            .path = "/components",
                            .expected = "names starting with '" + m.name + ".'",
                            .found = "'" + c + "'"});
  return m;
}

void ModuleContext::add_component(const TypeDesc& type) {
  if (std::find(manifest_.components.begin(), manifest_.components.end(), type.name) ==
      manifest_.components.end())
    throw Error(ErrorInfo{.file = manifest_.origin, .path = "/components",
                          .message = "module '" + manifest_.name + "' registers component '" + type.name +
                                     "' that its manifest does not declare"});
  world_.modules().register_component(type, manifest_.name);
}

void ModuleContext::system(SystemDesc s) { world_.scheduler().add(std::move(s)); }

void ModuleHost::add_search_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return;
  search_dirs_.push_back(dir);
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().filename().string().ends_with(".module.json")) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    // One bad manifest costs its own module only: it is reported and skipped, the others still load.
    ModuleManifest m;
    try {
      m = parse_module_manifest(read_file_text(f.string(), kMaxJsonBytes), f.string());
    } catch (const Error& e) {
      problems_.emplace_back(e.what());
      log::warn(std::string("skipped module manifest: ") + e.what());
      continue;
    }
    if (!m.library.empty()) m.library = f.parent_path() / m.library;
    if (!m.data_dir.empty() && m.data_dir.is_relative()) m.data_dir = f.parent_path() / m.data_dir;
    if (!manifests_.count(m.name)) manifests_.emplace(m.name, std::move(m));
  }
}

void ModuleHost::add_static(const ModuleDefinition& def) {
  ModuleManifest m = parse_module_manifest(def.manifest_json, "static module");
  m.origin = "static module '" + m.name + "'";
  // A manifest found in a search folder says where this installation keeps the module's data; the
  // compiled-in source folder is the fallback (tests, programs run from the build tree).
  auto found = manifests_.find(m.name);
  m.data_dir = found != manifests_.end() && !found->second.data_dir.empty() ? found->second.data_dir
               : def.data_dir                                               ? def.data_dir
                                                                            : "";
  static_defs_[m.name] = &def;
  manifests_[m.name] = std::move(m);  // a static module wins over a plugin of the same name
}

std::vector<ModuleManifest> ModuleHost::available() const {
  std::vector<ModuleManifest> out;
  for (const auto& [name, m] : manifests_) out.push_back(m);
  return out;
}

const ModuleManifest* ModuleHost::manifest(std::string_view module) const {
  auto it = manifests_.find(module);
  return it == manifests_.end() ? nullptr : &it->second;
}

const ModuleManifest* ModuleHost::provider_of(std::string_view component) const {
  for (const auto& [name, m] : manifests_)
    if (std::find(m.components.begin(), m.components.end(), component) != m.components.end()) return &m;
  return nullptr;
}

bool ModuleHost::is_loaded(std::string_view module) const {
  return std::find(load_order_.begin(), load_order_.end(), module) != load_order_.end();
}

void ModuleHost::load(std::string_view module) {
  std::vector<std::string> stack;
  load_with_stack(module, stack);
}

void ModuleHost::load_with_stack(std::string_view module, std::vector<std::string>& stack) {
  if (is_loaded(module)) return;
  if (std::find(stack.begin(), stack.end(), module) != stack.end()) {
    std::string cycle;
    for (const auto& s : stack) cycle += s + " -> ";
    throw Error("module dependency cycle: " + cycle + std::string(module));
  }
  const ModuleManifest* m = manifest(module);
  if (!m) {
    std::string where;
    for (const auto& d : search_dirs_) where += (where.empty() ? "" : ", ") + d.string();
    throw Error(ErrorInfo{.message = "module '" + std::string(module) + "' is not installed" +
                                     (stack.empty() ? "" : " (needed by '" + stack.back() + "')") +
                                     "; searched: " + (where.empty() ? "no module folders" : where) +
                                     (problems_.empty()
                                          ? ""
                                          : "; skipped " + std::to_string(problems_.size()) +
                                                " unreadable manifest(s), the first: " + problems_.front())});
  }
  stack.emplace_back(module);
  for (const auto& dep : m->depends) {
    // A missing dependency says itself which module needs it; any other failure is wrapped here.
    if (!manifest(dep) || is_loaded(dep) || std::find(stack.begin(), stack.end(), dep) != stack.end()) {
      load_with_stack(dep, stack);
      continue;
    }
    try {
      load_with_stack(dep, stack);
    } catch (const Error& e) {
      throw Error(ErrorInfo{.message = "module '" + m->name + "' needs module '" + dep +
                                       "', which cannot be loaded: " + e.what()});
    }
  }
  stack.pop_back();

  const ModuleDefinition* def = nullptr;
  if (auto it = static_defs_.find(module); it != static_defs_.end()) {
    def = it->second;
  } else {
    void* handle = dlopen(m->library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
      throw Error(
          ErrorInfo{.file = m->origin, .message = "cannot load module library: " + std::string(dlerror())});
    using EntryFn = const ModuleDefinition* (*)(unsigned*);
    auto entry = reinterpret_cast<EntryFn>(dlsym(handle, WELKIN_MODULE_ENTRY_NAME));
    if (!entry)
      throw Error(ErrorInfo{.file = m->library.string(),
                            .message = "not a Welkin module: no entry point " WELKIN_MODULE_ENTRY_NAME});
    unsigned abi = 0;
    def = entry(&abi);
    if (abi != kModuleAbiVersion)
      throw Error(ErrorInfo{.file = m->library.string(),
                            .expected = "module ABI " + std::to_string(kModuleAbiVersion),
                            .found = "ABI " + std::to_string(abi),
                            .message = "incompatible module '" + m->name + "'"});
    ModuleManifest built = parse_module_manifest(def->manifest_json, m->library.string());
    if (built.name != m->name || built.version != m->version || built.components != m->components ||
        built.depends != m->depends || built.uses != m->uses)
      throw Error(ErrorInfo{.file = m->origin, .expected = built.name + " " + built.version + " (as built)",
                            .found = m->name + " " + m->version,
                            .message = "incompatible module: the manifest does not match its library"});
  }
  ModuleContext ctx(world_, *m);
  def->register_fn(ctx);
  for (const auto& c : m->components)
    if (!component(c))
      throw Error(ErrorInfo{
          .file = m->origin,
          .path = "/components",
          .message = "module '" + m->name + "' declares component '" + c + "' but does not register it"});
  load_order_.emplace_back(module);
  log::info("loaded module " + m->name + " " + m->version);
}

const ComponentInfo& ModuleHost::require_component(std::string_view name) {
  if (const ComponentInfo* c = component(name)) return *c;
  const ModuleManifest* m = provider_of(name);
  if (!m) {
    std::string mod(name.substr(0, name.find('.')));
    throw Error(ErrorInfo{
        .expected = "a known component",
        .found = "'" + std::string(name) + "'",
        .message = manifest(mod) ? "module '" + mod + "' has no such component"
                                 : "unknown component (no installed module '" + mod + "' provides it)"});
  }
  load(m->name);
  return *component(name);
}

const ComponentInfo* ModuleHost::component(std::string_view name) const {
  return component(type_id_of_name(name));
}
const ComponentInfo* ModuleHost::component(TypeId id) const {
  auto it = components_.find(id);
  return it == components_.end() ? nullptr : &it->second;
}

void ModuleHost::register_component(const TypeDesc& type, const std::string& module) {
  auto [it, inserted] = components_.emplace(type.id, ComponentInfo{&type, module});
  if (!inserted && it->second.type->name != type.name)
    throw Error("component id collision between '" + type.name + "' and '" + it->second.type->name + "'");
}

}  // namespace welkin
