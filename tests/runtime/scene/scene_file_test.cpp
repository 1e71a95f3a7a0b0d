#include "welkin/scene/scene_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/json_fields.h"
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

fs::path temp_dir() {
  return welkin::testing::scratch_folder("welkin-scene-test");
}

welkin::ErrorInfo load_error(const std::string& text) {
  fs::path f = temp_dir() / "bad.json";
  std::ofstream(f) << text;
  welkin::World world;
  try {
    welkin::load_scene_file(world, f.string());
  } catch (const welkin::Error& e) {
    EXPECT_EQ(world.registry().alive_count(), 0u) << "a failed load leaves no entity behind";
    welkin::ErrorInfo info = e.info();
    info.file = info.file.substr(0, info.file.find(':')) == f.string() ? "bad.json" + info.file.substr(f.string().size()) : info.file;
    return info;
  }
  ADD_FAILURE() << "no error for: " << text;
  return {};
}

TEST(SceneFile, LoadSaveRoundTripsExactly) {
  welkin::World a;
  welkin::load_scene_file(a, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  EXPECT_EQ(a.registry().alive_count(), 5u);
  json saved = welkin::save_scene(a);
  welkin::World b;
  welkin::load_scene(b, saved, "saved");
  EXPECT_EQ(welkin::save_scene(b), saved);
  auto cam = b.registry().first<welkin::Camera>();
  EXPECT_EQ(b.registry().get<welkin::Camera>(cam)->heading_deg, 10.0f);
  EXPECT_EQ(b.registry().get<welkin::Camera>(cam)->ev100, 13.5f);
  EXPECT_EQ(b.registry().get<welkin::Name>(cam)->value, "camera");
}

TEST(SceneFile, TheExplicitModulesListSurvivesARoundTrip) {
  // "core" is listed without a core component in the scene: only the list says it is wanted.
  welkin::World a;
  welkin::load_scene(a, json::parse(R"({"welkin_scene": 1, "modules": ["core"], "entities": [{"name": "x"}]})"), "m.json");
  json saved = welkin::save_scene(a);
  EXPECT_EQ(saved["modules"], json::array({"core"})) << saved.dump();
  welkin::World b;
  welkin::load_scene(b, saved, "saved.json");
  EXPECT_EQ(welkin::save_scene(b), saved);
  // A scene without the list saves without it.
  welkin::World c;
  welkin::load_scene(c, json::parse(R"({"welkin_scene": 1, "entities": []})"), "plain.json");
  EXPECT_FALSE(welkin::save_scene(c).contains("modules"));
}

TEST(SceneFile, SaveIsAtomicAndKeepsTheOldFileOnFailure) {
  fs::path dir = temp_dir();
  fs::path f = dir / "keep.json";
  welkin::World w;
  welkin::load_scene_file(w, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  welkin::save_scene_file(w, f.string());
  std::string before = slurp(f);
  EXPECT_NE(before.find("core.Camera"), std::string::npos);
  // A read-only folder makes the temporary file impossible: the save fails, the file survives.
  if (::geteuid() != 0) {
    ::chmod(dir.c_str(), 0555);
    EXPECT_THROW(welkin::save_scene_file(w, f.string()), welkin::Error);
    ::chmod(dir.c_str(), 0755);
    EXPECT_EQ(slurp(f), before);
  }
  // Saving into a missing folder fails with a clear error instead of a crash.
  EXPECT_THROW(welkin::save_scene_file(w, (dir / "missing" / "x.json").string()), welkin::Error);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* path;      // expected error path
  const char* contains;  // expected fragment of the message
};

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, GivesOneClearError) {
  const BadCase& c = GetParam();
  welkin::ErrorInfo e = load_error(c.text);
  EXPECT_EQ(e.path, c.path) << welkin::format_error(e);
  EXPECT_NE(welkin::format_error(e).find(c.contains), std::string::npos) << welkin::format_error(e);
  EXPECT_EQ(e.file.rfind("bad.json", 0), 0u) << "the error names the file: " << e.file;
}

const char* kCamera = R"({"core.Camera": {}})";
std::string with_components(const std::string& comps) {
  return R"({"welkin_scene": 1, "entities": [{"name": "c", "components": )" + std::string(kCamera) +
         R"(}, {"components": )" + comps + "}]}";
}
const std::string kUnknownComponent = with_components(R"({"core.Nonsense": {}})");
const std::string kUnknownModule = with_components(R"({"clouds.VolumetricClouds": {"coverage": 0.5}})");
const std::string kUnknownField = with_components(R"({"core.DebugShape": {"radius": 1}})");
const std::string kWrongType = with_components(R"({"core.DebugShape": {"albedo": "red"}})");
const std::string kOutOfRange = with_components(R"({"core.DebugShape": {"albedo": [0.5, 2.0, 0.5]}})");
const std::string kNaN = with_components(R"({"core.DebugShape": {"size_m": [NaN, 1, 1]}})");
const std::string kOverflow = with_components(R"({"core.DebugShape": {"size_m": [1e999, 1, 1]}})");
const std::string kBadEnum = with_components(R"({"core.DebugShape": {"shape": "cone"}})");
const std::string kDuplicateComponent = R"({"welkin_scene": 1, "entities": [{"components": {"core.Camera": {}, "core.Camera": {}}}]})";

INSTANTIATE_TEST_SUITE_P(Cases, BadScene, ::testing::Values(
    BadCase{"unknown_component", kUnknownComponent.c_str(), "/entities/1/components/core.Nonsense", "no such component"},
    BadCase{"missing_module", kUnknownModule.c_str(), "/entities/1/components/clouds.VolumetricClouds", "no installed module 'clouds'"},
    BadCase{"unknown_field", kUnknownField.c_str(), "/entities/1/components/core.DebugShape/radius", "unknown field"},
    BadCase{"wrong_type", kWrongType.c_str(), "/entities/1/components/core.DebugShape/albedo", "found \"red\""},
    BadCase{"out_of_range", kOutOfRange.c_str(), "/entities/1/components/core.DebugShape/albedo/1", "out of range"},
    BadCase{"nan", kNaN.c_str(), "", "malformed JSON"},
    BadCase{"overflow", kOverflow.c_str(), "", "number overflow"},
    BadCase{"bad_enum", kBadEnum.c_str(), "/entities/1/components/core.DebugShape/shape", "\"sphere\", \"box\""},
    BadCase{"truncated", R"({"welkin_scene": 1, "entities": [{"components": {"core.Camera": {"ev100": 1)", "", "truncated"},
    BadCase{"empty", "", "", "empty"},
    BadCase{"not_object", "[1, 2]", "/", "expected a scene object"},
    BadCase{"no_version", R"({"entities": []})", "/welkin_scene", "expected key \"welkin_scene\""},
    BadCase{"future_version", R"({"welkin_scene": 9, "entities": []})", "/welkin_scene", "scene format version 1"},
    BadCase{"unknown_top_key", R"({"welkin_scene": 1, "entities": [], "entites": []})", "/entites", "unknown key"},
    BadCase{"entities_not_array", R"({"welkin_scene": 1, "entities": {}})", "/entities", "array of entities"},
    BadCase{"entity_typo", R"({"welkin_scene": 1, "entities": [{"componets": {}}]})", "/entities/0/componets", "unknown key"}
), [](const auto& info) { return std::string(info.param.name); });

TEST(SceneFile, DuplicateJsonKeysAreRefusedWithTheirPath) {
  // nlohmann alone keeps the last of duplicate keys, silently; the reader names the second one.
  welkin::ErrorInfo e = load_error(kDuplicateComponent);
  EXPECT_EQ(e.path, "/entities/0/components/core.Camera") << welkin::format_error(e);
  EXPECT_NE(welkin::format_error(e).find("duplicate key"), std::string::npos) << welkin::format_error(e);
  EXPECT_EQ(load_error(R"({"welkin_scene": 1, "welkin_scene": 1, "entities": []})").path, "/welkin_scene");
  EXPECT_EQ(load_error(R"({"welkin_scene": 1, "entities": [{}, {"name": "a", "components": {}, "name": "b"}]})").path,
            "/entities/1/name");
  // Equal keys in different objects are no duplicates.
  EXPECT_NO_THROW(welkin::parse_json_text(R"({"a": {"x": 1}, "b": {"x": [{"x": 2}, {"x": 3}]}})", "ok.json"));
}

TEST(SceneFile, JsonDepthAndSizeAreBoundedBeforeParsing) {
  std::string deep = R"({"welkin_scene": 1, "entities": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
  welkin::ErrorInfo e = load_error(deep);
  EXPECT_NE(welkin::format_error(e).find("nested at most 64 levels deep"), std::string::npos) << welkin::format_error(e);
  EXPECT_EQ(e.file, "bad.json:1:96");
  std::string big = R"({"welkin_scene": 1, "entities": [], "pad": ")" + std::string(welkin::kMaxJsonBytes, ' ') + "\"}";
  e = load_error(big);
  EXPECT_NE(welkin::format_error(e).find("bad.json: file is 16777262 bytes; the limit is 16777216"), std::string::npos) << welkin::format_error(e);
  // Text that never was a file (a script's inline JSON, the clipboard) meets the same bound.
  try {
    welkin::parse_json_text(big, "inline");
    ADD_FAILURE() << "no error for 16 MiB of text";
  } catch (const welkin::Error& err) {
    EXPECT_NE(std::string(err.what()).find("expected JSON of at most 16777216 bytes"), std::string::npos) << err.what();
  }
}

TEST(SceneFile, AFifoOrADeviceIsRefusedNotRead) {
  ::alarm(20);  // a reader that waits for a writer fails the test instead of hanging it
  fs::path fifo = temp_dir() / "pipe.json";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  welkin::World w;
  try {
    welkin::load_scene_file(w, fifo.string());
    ADD_FAILURE() << "a FIFO was read";
  } catch (const welkin::Error& err) {
    EXPECT_EQ(std::string(err.what()), fifo.string() + ": cannot read a FIFO (named pipe); expected a regular file");
  }
  EXPECT_THROW(welkin::load_scene_file(w, "/dev/zero"), welkin::Error);
  ::alarm(0);
}

TEST(SceneFile, ErrorLineAndColumnForSyntaxErrors) {
  welkin::ErrorInfo e = load_error("{\n  \"welkin_scene\": 1,\n  \"entities\": [,]\n}");
  EXPECT_EQ(e.file, "bad.json:3:16");
}

}  // namespace
