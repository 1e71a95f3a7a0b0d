// The runtime's readers (scene, sequence, module manifest) do work linear in their input: each is fed
// 1x, 10x and 100x a pathological document (many keys, many unknown names, many entities, long
// strings) and its time may grow by about 10x per step, not 100x (growth.h). Hostile files are
// refused with one error naming the file and the path, however many bad names they hold.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "growth.h"
#include "welkin/core/error.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"
#include "welkin/scene/sequence.h"

namespace {

using nlohmann::json;
using welkin::testing::measure_growth;

// {"welkin_scene": 1, "entities": [{"components": {"x.Unknown0": {}, "x.Unknown1": {}, ...}}]}: the
// shape of the 5.9 MB file with 400 000 names that once took minutes.
std::string scene_with_unknown_components(size_t names) {
  std::string s = R"({"welkin_scene": 1, "entities": [{"name": "e", "components": {)";
  for (size_t i = 0; i < names; ++i) s += (i ? ", " : "") + ("\"x.Unknown" + std::to_string(i) + "\": {}");
  return s + "}}]}";
}

welkin::ErrorInfo load_error(const std::string& text, const std::string& file) {
  welkin::World world;
  try {
    welkin::load_scene(world, welkin::parse_json_text(text, file), file);
  } catch (const welkin::Error& e) {
    return e.info();
  }
  return {};
}

TEST(ReaderGrowth, SceneWithManyUnknownComponentsIsRefusedAtTheFirst) {
  auto g = measure_growth(500, scene_with_unknown_components,
                          [](const std::string& text) { load_error(text, "many.json"); });
  EXPECT_TRUE(g.linear()) << g.describe();
  welkin::ErrorInfo e = load_error(scene_with_unknown_components(2000), "many.json");
  EXPECT_EQ(e.file, "many.json");
  EXPECT_EQ(e.path, "/entities/0/components/x.Unknown0");  // the first, and only that one
  EXPECT_EQ(e.found, "'x.Unknown0'");
}

TEST(ReaderGrowth, SceneComponentNamesOfManyEntitiesAndNames) {
  // Every entity names the same few components and one of its own: the list is built once per name.
  auto make = [](size_t n) {
    json ents = json::array();
    for (size_t i = 0; i < n; ++i)
      ents.push_back(
          {{"name", "e" + std::to_string(i)},
           {"components", {{"core.Camera", json::object()}, {"x.Own" + std::to_string(i), json::object()}}}});
    return json{{"welkin_scene", 1}, {"entities", std::move(ents)}};
  };
  auto g =
      measure_growth(300, make, [](const json& doc) { welkin::scene_component_names(doc, "names.json"); });
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(welkin::scene_component_names(make(3), "names.json"),
            (std::vector<std::string>{"core.Camera", "x.Own0", "x.Own1", "x.Own2"}));
}

TEST(ReaderGrowth, SceneWithManyEntitiesLoads) {
  auto make = [](size_t n) {
    std::string s = R"({"welkin_scene": 1, "modules": [)";
    for (size_t i = 0; i < n; ++i) s += i ? ", \"core\"" : "\"core\"";
    s += R"(], "entities": [)";
    for (size_t i = 0; i < n; ++i)
      s += (i ? ", " : "") + (R"({"name": "entity )" + std::to_string(i) +
                              R"(", "components": {"core.Camera": {"ev100": 12}}})");
    return s + "]}";
  };
  auto load = [](const std::string& text) {
    welkin::World world;
    welkin::load_scene(world, welkin::parse_json_text(text, "entities.json"), "entities.json");
    return world.registry().alive_count();
  };
  auto g = measure_growth(100, make, load);
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(load(make(250)), 250u);
}

TEST(ReaderGrowth, SceneWithALongNameAndALongUnknownKey) {
  auto make = [](size_t n) {
    std::string name(n * 100, 'n'), key(n * 100, 'k');
    return R"({"welkin_scene": 1, "entities": [{"name": ")" + name + R"("}, {")" + key + R"(": 1}]})";
  };
  auto g = measure_growth(400, make, [](const std::string& text) { load_error(text, "long.json"); });
  EXPECT_TRUE(g.linear()) << g.describe();
  welkin::ErrorInfo e = load_error(make(1), "long.json");
  EXPECT_EQ(e.path, "/entities/1/" + std::string(100, 'k'));
  EXPECT_EQ(e.message, "unknown key");
}

TEST(ReaderGrowth, JsonWithManyKeysAndADuplicateAtTheEnd) {
  auto make = [](size_t n) {
    std::string s = "{";
    for (size_t i = 0; i < n; ++i) s += "\"k" + std::to_string(i) + "\": [" + std::to_string(i) + "], ";
    return s + "\"k0\": 0}";
  };
  auto parse = [](const std::string& text) {
    try {
      welkin::parse_json_text(text, "keys.json");
    } catch (const welkin::Error& e) {
      return e.info().path;
    }
    return std::string("no error");
  };
  auto g = measure_growth(1000, make, parse);
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(parse(make(10)), "/k0");
}

// {"welkin_sequence": 1, "tracks": [n tracks of n/10 + 1 keys each, values as long arrays]}
std::string sequence_text(size_t n, const std::string& last_key_extra = {}) {
  std::string s =
      R"({"welkin_sequence": 1, "description": ")" + std::string(n * 10, 'd') + R"(", "tracks": [)";
  for (size_t t = 0; t < n; ++t) {
    s += (t ? ", " : "") + std::string(R"({"target": "core.Camera/ev100", "entity": "cam", "keys": [)");
    for (size_t k = 0; k < 4; ++k)
      s += (k ? ", " : "") + ("{\"t\": " + std::to_string(k) + ", \"value\": " + std::to_string(k) + "}");
    s += "]}";
  }
  return s + "]" + last_key_extra + "}";
}

welkin::ErrorInfo sequence_error(const std::string& text) {
  try {
    welkin::parse_sequence(welkin::parse_json_text(text, "seq.json"), "seq.json");
  } catch (const welkin::Error& e) {
    return e.info();
  }
  return {};
}

TEST(ReaderGrowth, SequenceWithManyTracksAndKeys) {
  auto parse = [](const std::string& text) {
    return welkin::parse_sequence(welkin::parse_json_text(text, "seq.json"), "seq.json");
  };
  auto g = measure_growth(
      100, [](size_t n) { return sequence_text(n); }, parse);
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(parse(sequence_text(30)).tracks.size(), 30u);
}

TEST(ReaderGrowth, SequenceWithOneLongTrackAndManyUnknownKeys) {
  auto make = [](size_t n) {
    std::string s = R"({"welkin_sequence": 1, "tracks": [{"target": "core.Camera/ev100", "keys": [)";
    for (size_t k = 0; k < n; ++k)
      s += (k ? ", " : "") + ("{\"t\": " + std::to_string(k) + ", \"value\": [1, 2, 3]}");
    s += "]}]";
    for (size_t k = 0; k < n; ++k) s += ", \"unknown" + std::to_string(k) + "\": 0";
    return s + "}";
  };
  auto g = measure_growth(200, make, sequence_error);
  EXPECT_TRUE(g.linear()) << g.describe();
  welkin::ErrorInfo e = sequence_error(make(20));
  EXPECT_EQ(e.file, "seq.json");
  EXPECT_EQ(e.path, "/unknown0");  // the first unknown key, and only that one
}

TEST(ReaderGrowth, ModuleManifestWithManyComponentsAndALongDescription) {
  auto make = [](size_t n) {
    std::string name = "mod";
    std::string s = R"({"name": "mod", "version": "1", "description": ")" + std::string(n * 20, 'd') +
                    R"(", "depends": [)";
    for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + ("\"dep" + std::to_string(i) + "\"");
    s += R"(], "components": [)";
    for (size_t i = 0; i < n; ++i) s += (i ? ", \"" : "\"") + name + ".C" + std::to_string(i) + "\"";
    return s + ", \"other.Last\"]}";  // the last one is not the module's: refused after every check
  };
  auto parse = [](const std::string& text) {
    try {
      welkin::parse_module_manifest(text, "big.module.json");
    } catch (const welkin::Error& e) {
      return e.info();
    }
    return welkin::ErrorInfo{};
  };
  auto g = measure_growth(300, make, parse);
  EXPECT_TRUE(g.linear()) << g.describe();
  welkin::ErrorInfo e = parse(make(3));
  EXPECT_EQ(e.file, "big.module.json");
  EXPECT_EQ(e.path, "/components");
  EXPECT_EQ(e.found, "'other.Last'");
}

}  // namespace
