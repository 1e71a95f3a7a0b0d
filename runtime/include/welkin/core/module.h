#pragma once
// Modules are plugins: each is a shared library with one entry point returning its definition
// (manifest + registration function). Manifests are data, readable without loading the library,
// so the runtime knows which module provides which component and loads only what a scene uses.
// A static build passes the same definitions to ModuleHost::add_static.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "welkin/core/reflection.h"
#include "welkin/core/system.h"

namespace welkin {

class World;

// Bumped when the runtime's binary interface seen by plugins changes.
inline constexpr unsigned kModuleAbiVersion = 1;

struct ModuleManifest {
  std::string name;
  std::string version;
  std::string description;
  // Modules this one cannot work without: loaded before it; a missing or unloadable one is an error.
  std::vector<std::string> depends;
  // Modules whose part of the shared state (welkin/scene/shared_state.h) this one reads when the
  // scene has them; not loaded for it.
  std::vector<std::string> uses;
  std::vector<std::string> components;  // full names, "module.Type"
  std::filesystem::path library;        // empty for static modules
  std::filesystem::path data_dir;       // shaders/, presets/ live here
  std::string origin;                   // manifest file, or "static"
};

// Parses a manifest; throws welkin::Error naming `origin` and the JSON path on any problem.
ModuleManifest parse_module_manifest(const std::string& json_text, const std::string& origin);

class ModuleContext;
using ModuleRegisterFn = void (*)(ModuleContext&);

struct ModuleDefinition {
  const char* manifest_json;  // the module's module.json, embedded at build time
  const char* data_dir;       // the module's source folder (used by static builds and tests)
  ModuleRegisterFn register_fn;
};

// What a module's registration function receives.
class ModuleContext {
 public:
  ModuleContext(World& world, const ModuleManifest& manifest) : world_(world), manifest_(manifest) {}
  template <class T> void component() { add_component(type_desc<T>()); }
  void add_component(const TypeDesc& type);
  void system(SystemDesc system);
  World& world() { return world_; }
  const ModuleManifest& manifest() const { return manifest_; }

 private:
  World& world_;
  const ModuleManifest& manifest_;
};

struct ComponentInfo {
  const TypeDesc* type = nullptr;
  std::string module;
};

class ModuleHost {
 public:
  explicit ModuleHost(World& world) : world_(world) {}

  // Reads every *.module.json in dir (plugins are loaded later, on demand). A manifest that cannot
  // be read is logged, listed in manifest_problems() and skipped; the other modules stay usable.
  void add_search_dir(const std::filesystem::path& dir);
  const std::vector<std::string>& manifest_problems() const { return problems_; }
  void add_static(const ModuleDefinition& def);
  std::vector<ModuleManifest> available() const;
  const ModuleManifest* manifest(std::string_view module) const;
  // The module that declares a component, or nullptr.
  const ModuleManifest* provider_of(std::string_view component) const;

  // Loads a module and its dependencies first; no-op when already loaded. Throws welkin::Error.
  void load(std::string_view module);
  bool is_loaded(std::string_view module) const;
  std::vector<std::string> loaded() const { return load_order_; }
  // Ensures the component's module is loaded and returns its registration, or throws.
  const ComponentInfo& require_component(std::string_view component);

  const ComponentInfo* component(std::string_view name) const;
  const ComponentInfo* component(TypeId id) const;
  void register_component(const TypeDesc& type, const std::string& module);
  std::vector<std::filesystem::path> search_dirs() const { return search_dirs_; }

 private:
  void load_with_stack(std::string_view module, std::vector<std::string>& stack);
  World& world_;
  std::map<std::string, ModuleManifest, std::less<>> manifests_;
  std::map<std::string, const ModuleDefinition*, std::less<>> static_defs_;
  std::vector<std::string> load_order_;
  std::map<TypeId, ComponentInfo> components_;
  std::vector<std::filesystem::path> search_dirs_;
  std::vector<std::string> problems_;  // one formatted Error per skipped manifest
};

}  // namespace welkin

// Exported plugin entry point (generated per module by CMake; see cmake/WelkinModule.cmake).
#define WELKIN_MODULE_ENTRY_NAME "welkin_module_entry"
