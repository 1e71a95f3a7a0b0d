#include "welkin/scene/scene_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <unordered_set>

#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace welkin {

using nlohmann::json;

void describe(TypeBuilder<Name>& t) { t.field("value", &Name::value).tooltip("Display name"); }

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& expected,
                       const json& found, const std::string& message = {}) {
  throw Error(ErrorInfo{
      .file = file, .path = path, .expected = expected, .found = describe_json(found), .message = message});
}

const json& require_key(const json& obj, const char* key, const std::string& file, const std::string& path) {
  auto it = obj.find(key);
  if (it == obj.end())
    throw Error(ErrorInfo{.file = file,
                          .path = path + "/" + key,
                          .expected = std::string("key \"") + key + "\"",
                          .found = "nothing"});
  return *it;
}

void check_header(const json& doc, const std::string& file) {
  if (!doc.is_object()) fail(file, "/", "a scene object", doc);
  const json& v = require_key(doc, "welkin_scene", file, "");
  if (!v.is_number_integer() || v.get<int64_t>() != kSceneFormatVersion)
    fail(file, "/welkin_scene", "scene format version " + std::to_string(kSceneFormatVersion), v);
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "welkin_scene" && it.key() != "entities" && it.key() != "modules")
      fail(file, "/" + it.key(), "one of \"welkin_scene\", \"modules\", \"entities\"", json(it.key()),
           "unknown key");
  const json& ents = require_key(doc, "entities", file, "");
  if (!ents.is_array()) fail(file, "/entities", "array of entities", ents);
}

// The document's shape: header, entity objects, component objects. Calls `component` with each
// entity's components object.
template <class Fn> void check_shape(const json& doc, const std::string& file, Fn&& components) {
  check_header(doc, file);
  const json& ents = doc["entities"];
  for (size_t i = 0; i < ents.size(); ++i) {
    if (!ents[i].is_object()) fail(file, "/entities/" + std::to_string(i), "entity object", ents[i]);
    auto comps = ents[i].find("components");
    if (comps == ents[i].end()) continue;
    if (!comps->is_object())
      fail(file, "/entities/" + std::to_string(i) + "/components", "object of components", *comps);
    components(*comps);
  }
}

}  // namespace

std::vector<std::string> scene_component_names(const json& doc, const std::string& file) {
  std::vector<std::string> names;
  std::unordered_set<std::string_view>
      seen;  // a scene may name very many components: no linear search per name
  check_shape(doc, file, [&](const json& comps) {
    for (auto it = comps.begin(); it != comps.end(); ++it)
      if (seen.insert(it.key()).second) names.push_back(it.key());
  });
  return names;
}

void load_scene(World& world, const json& doc, const std::string& file) {
  check_shape(doc, file, [](const json&) {});  // the document's shape first, before any module loads
  if (auto mods = doc.find("modules"); mods != doc.end()) {
    if (!mods->is_array()) fail(file, "/modules", "array of module names", *mods);
    for (size_t i = 0; i < mods->size(); ++i) {
      const json& m = (*mods)[i];
      if (!m.is_string()) fail(file, "/modules/" + std::to_string(i), "module name", m);
      try {
        world.modules().load(m.get<std::string>());
      } catch (const Error& e) {
        throw e.with_file(file).with_path_prefix("/modules/" + std::to_string(i));
      }
    }
    std::vector<std::string>& listed = world.resource<SceneModules>().names;
    std::unordered_set<std::string> known(listed.begin(), listed.end());
    for (const json& m : *mods)
      if (known.insert(m.get<std::string>()).second) listed.push_back(m.get<std::string>());
  }
  Registry& reg = world.registry();
  const json& ents = doc["entities"];
  // Build every entity in a scratch list first so a failure leaves no half-loaded entity behind.
  std::vector<Entity> created;
  try {
    for (size_t i = 0; i < ents.size(); ++i) {
      std::string ep = "/entities/" + std::to_string(i);
      const json& ej = ents[i];
      for (auto it = ej.begin(); it != ej.end(); ++it)
        if (it.key() != "name" && it.key() != "components")
          fail(file, ep + "/" + it.key(), "\"name\" or \"components\"", json(it.key()), "unknown key");
      Entity e = reg.create();
      created.push_back(e);
      if (auto n = ej.find("name"); n != ej.end()) {
        if (!n->is_string()) fail(file, ep + "/name", "string", *n);
        reg.emplace<Name>(e).value = n->get<std::string>();
      }
      auto comps = ej.find("components");
      if (comps == ej.end()) continue;
      for (auto it = comps->begin(); it != comps->end(); ++it) {
        std::string cp = ep + "/components/" + it.key();
        try {
          const ComponentInfo& info = world.modules().require_component(it.key());
          if (reg.has(e, info.type->id))
            fail(file, cp, "each component once per entity", json(it.key()), "duplicate component");
          object_from_json(*info.type, reg.emplace(e, *info.type), it.value());
        } catch (const Error& err) {
          throw err.with_file(file).with_path_prefix(err.info().file.empty() ? cp : "");
        }
      }
    }
  } catch (...) {
    for (Entity e : created) reg.destroy(e);
    throw;
  }
}

void load_scene_file(World& world, const std::string& path) { load_scene(world, read_json_file(path), path); }

json save_scene(const World& world) {
  const Registry& reg = world.registry();
  json ents = json::array();
  for (Entity e : reg.entities()) {
    json ej = json::object();
    if (const Name* n = reg.get<Name>(e)) ej["name"] = n->value;
    json comps = json::object();
    for (const TypeDesc* t : reg.components_of(e)) {
      if (t->id == type_id<Name>()) continue;
      comps[t->name] = object_to_json(*t, reg.get(e, t->id));
    }
    ej["components"] = std::move(comps);
    ents.push_back(std::move(ej));
  }
  json doc{{"welkin_scene", kSceneFormatVersion}, {"entities", std::move(ents)}};
  if (const SceneModules* listed = world.find_resource<SceneModules>(); listed && !listed->names.empty())
    doc["modules"] = listed->names;
  return doc;
}

void save_scene_file(const World& world, const std::string& path) {
  write_file_atomically(path, save_scene(world).dump(2) + "\n");
}

}  // namespace welkin
