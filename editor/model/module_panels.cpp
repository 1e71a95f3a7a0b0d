#include "model/module_panels.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <unordered_set>

#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& expected, const json& found) {
  throw Error(ErrorInfo{.file = file, .path = path, .expected = expected, .found = describe_json(found)});
}

std::vector<ModulePanelSpec> parse_panels(const ModuleManifest& m, const json& doc, const std::string& file) {
  if (!doc.is_object() || !doc.contains("panels")) fail(file, "/panels", "{\"panels\": [...]}", doc);
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "panels") fail(file, "/" + it.key(), "only \"panels\"", json(it.key()));
  const json& panels = doc["panels"];
  if (!panels.is_array()) fail(file, "/panels", "array of panels", panels);
  std::vector<ModulePanelSpec> out;
  // Looked up once per listed component: a long list against a long manifest stays linear.
  const std::unordered_set<std::string> declared(m.components.begin(), m.components.end());
  for (size_t i = 0; i < panels.size(); ++i) {
    std::string pp = "/panels/" + std::to_string(i);
    const json& p = panels[i];
    if (!p.is_object()) fail(file, pp, "panel object {\"title\", \"components\" or \"map\"}", p);
    for (auto it = p.begin(); it != p.end(); ++it)
      if (it.key() != "title" && it.key() != "components" && it.key() != "map")
        fail(file, pp + "/" + it.key(), "\"title\", \"components\" or \"map\"", json(it.key()));
    ModulePanelSpec spec{.module = m.name};
    if (!p.contains("title") || !p["title"].is_string() || p["title"].get<std::string>().empty())
      fail(file, pp + "/title", "a non-empty title", p.value("title", json("nothing")));
    spec.title = p["title"].get<std::string>();
    auto component_of_module = [&](const json& name, const std::string& at) {
      if (!name.is_string()) fail(file, at, "component name", name);
      if (!declared.count(name.get_ref<const std::string&>()))
        fail(file, at, "a component module '" + m.name + "' declares", name);
      return name.get<std::string>();
    };
    if (p.contains("map") == p.contains("components")) fail(file, pp, "either \"components\" or \"map\"", p);
    if (p.contains("map")) {
      const json& mp = p["map"];
      const std::string at = pp + "/map";
      if (!mp.is_object()) fail(file, at, "{\"component\", \"file_field\", \"size_field\"}", mp);
      for (auto it = mp.begin(); it != mp.end(); ++it)
        if (it.key() != "component" && it.key() != "file_field" && it.key() != "size_field")
          fail(file, at + "/" + it.key(), "\"component\", \"file_field\" or \"size_field\"", json(it.key()));
      MapFieldSpec map{.component = component_of_module(mp.value("component", json()), at + "/component")};
      for (auto [key, out_field] : {std::pair{"file_field", &map.file_field}, std::pair{"size_field", &map.size_field}}) {
        const json& f = mp.value(key, json());
        if (!f.is_string() || f.get<std::string>().empty()) fail(file, at + "/" + key, "a field name", f);
        *out_field = f.get<std::string>();
      }
      spec.map = std::move(map);
    } else {
      const json& comps = p["components"];
      if (!comps.is_array() || comps.empty()) fail(file, pp + "/components", "a non-empty array of component names", comps);
      for (size_t c = 0; c < comps.size(); ++c) spec.components.push_back(component_of_module(comps[c], pp + "/components/" + std::to_string(c)));
    }
    out.push_back(std::move(spec));
  }
  return out;
}

}  // namespace

std::vector<ModulePanelSpec> read_module_panels(const ModuleHost& modules, std::vector<std::string>& errors) {
  std::vector<ModulePanelSpec> out;
  for (const ModuleManifest& m : modules.available()) {
    if (m.data_dir.empty()) continue;
    std::filesystem::path file = m.data_dir / "editor" / "panels.json";
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) continue;
    try {
      auto specs = parse_panels(m, read_json_file(file.string()), file.string());
      out.insert(out.end(), specs.begin(), specs.end());
    } catch (const Error& e) {
      errors.push_back(format_error(e.info()));
    }
  }
  return out;
}

}  // namespace welkin::editor
