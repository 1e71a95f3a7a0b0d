// Plugin loading with real shared libraries built from tests/runtime/plugins.
#include <gtest/gtest.h>

#include "error_of.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/scene_file.h"
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
const fs::path kModules = WELKIN_BINARY_DIR "/test-modules";

using welkin::testing::error_of;

json scene_with(const json& components) {
  return json{{"welkin_scene", 1}, {"entities", json::array({json{{"components", components}}})}};
}

TEST(Plugins, ManifestsAreReadWithoutLoadingLibraries) {
  welkin::World w;
  w.modules().add_search_dir(kModules);
  ASSERT_NE(w.modules().manifest("testsky"), nullptr);
  EXPECT_EQ(w.modules().manifest("testsky")->depends, std::vector<std::string>{"testbase"});
  EXPECT_EQ(w.modules().provider_of("testbase.Counter")->name, "testbase");
  EXPECT_EQ(w.modules().loaded(), std::vector<std::string>{"core"});
}

TEST(Plugins, SceneWithoutAModulesComponentsDoesNotLoadIt) {
  welkin::World w;
  w.modules().add_search_dir(kModules);
  welkin::load_scene(w, scene_with({{"core.Camera", json::object()}}), "plain.json");
  EXPECT_EQ(w.modules().loaded(), std::vector<std::string>{"core"});
  EXPECT_FALSE(w.modules().is_loaded("testsky"));
  EXPECT_FALSE(w.modules().is_loaded("testbase"));
}

TEST(Plugins, LoadsOnDemandWithDependenciesFirstAndRunsTheirSystems) {
  welkin::World w;
  w.modules().add_search_dir(kModules);
  welkin::load_scene(w, scene_with({{"testsky.Glow", {{"mode", "hard"}, {"layers", json::array({{{"coverage", 0.1}}})}}},
                                    {"testbase.Counter", {{"ticks", 5}}}}),
                     "plugin.json");
  EXPECT_EQ(w.modules().loaded(), (std::vector<std::string>{"core", "testbase", "testsky"}));
  auto ran = w.update({});
  EXPECT_EQ(ran, std::vector<std::string>{"testbase.tick"});
  json saved = welkin::save_scene(w);
  auto comps = saved["entities"][0]["components"];
  EXPECT_EQ(comps["testbase.Counter"]["ticks"], 6) << "the plugin's system ran once on the plugin's component";
  EXPECT_EQ(comps["testsky.Glow"]["mode"], "hard");
  EXPECT_EQ(comps["testsky.Glow"]["layers"][0]["coverage"], 0.1);
}

TEST(Plugins, MissingDependencyIsAClearError) {
  welkin::World w;
  w.modules().add_search_dir(kModules);
  std::string e = error_of([&] { welkin::load_scene(w, scene_with({{"testorphan.Thing", json::object()}}), "orphan.json"); });
  EXPECT_NE(e.find("module 'nosuchmodule' is not installed (needed by 'testorphan')"), std::string::npos) << e;
  EXPECT_NE(e.find("orphan.json"), std::string::npos) << e;
  EXPECT_NE(e.find("/entities/0/components/testorphan.Thing"), std::string::npos) << e;
}

TEST(Plugins, ManifestThatDoesNotMatchItsLibraryIsIncompatible) {
  fs::path dir = welkin::testing::scratch_folder("welkin-plugin-test");
  fs::create_directories(dir);
  fs::copy_file(kModules / "libwelkin_testbase.so", dir / "libwelkin_testbase.so", fs::copy_options::overwrite_existing);
  json m = json::parse(std::ifstream(kModules / "testbase.module.json"));
  m["version"] = "9.9.9";
  std::ofstream(dir / "testbase.module.json") << m.dump();
  welkin::World w;
  w.modules().add_search_dir(dir);
  std::string e = error_of([&] { w.modules().load("testbase"); });
  EXPECT_NE(e.find("incompatible module"), std::string::npos) << e;
  EXPECT_NE(e.find("found testbase 9.9.9"), std::string::npos) << e;
}

TEST(Plugins, AMalformedManifestIsReportedAndSkippedNotFatal) {
  fs::path dir = welkin::testing::scratch_folder("welkin-plugin-bad");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "broken.module.json") << R"({"name": "broken", "version": 3})";
  fs::copy_file(kModules / "libwelkin_testbase.so", dir / "libwelkin_testbase.so");
  fs::copy_file(kModules / "testbase.module.json", dir / "testbase.module.json");
  welkin::World w;
  EXPECT_NO_THROW(w.modules().add_search_dir(dir));
  ASSERT_EQ(w.modules().manifest_problems().size(), 1u);
  EXPECT_NE(w.modules().manifest_problems()[0].find("broken.module.json: at /version: expected string, found number"),
            std::string::npos) << w.modules().manifest_problems()[0];
  // The good module beside it still loads; asking for the broken one names the skipped manifest.
  EXPECT_NO_THROW(w.modules().load("testbase"));
  std::string e = error_of([&] { w.modules().load("broken"); });
  EXPECT_NE(e.find("module 'broken' is not installed"), std::string::npos) << e;
  EXPECT_NE(e.find("skipped 1 unreadable manifest(s), the first: " + (dir / "broken.module.json").string()), std::string::npos) << e;
}

TEST(Plugins, AManifestsLibraryIsAFileNameBesideIt) {
  fs::path dir = welkin::testing::scratch_folder("welkin-plugin-path");
  fs::remove_all(dir);
  fs::create_directories(dir);
  json m = json::parse(std::ifstream(kModules / "testbase.module.json"));
  for (const char* lib : {"../test-modules/libwelkin_testbase.so", "/usr/lib/libwelkin_testbase.so", ".."}) {
    m["library"] = lib;
    std::ofstream(dir / "testbase.module.json") << m.dump();
    welkin::World w;
    w.modules().add_search_dir(dir);
    EXPECT_EQ(w.modules().manifest("testbase"), nullptr) << lib;
    ASSERT_EQ(w.modules().manifest_problems().size(), 1u) << lib;
    EXPECT_NE(w.modules().manifest_problems()[0].find("at /library: expected a file name beside the manifest"),
              std::string::npos) << w.modules().manifest_problems()[0];
  }
}

TEST(Plugins, ADependencyThatCannotBeLoadedIsOneErrorNamingBoth) {
  // testsky depends on testbase, whose library here is not a library.
  fs::path dir = welkin::testing::scratch_folder("welkin-plugin-dep");
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* f : {"libwelkin_testsky.so", "testsky.module.json", "testbase.module.json"})
    fs::copy_file(kModules / f, dir / f);
  std::ofstream(dir / "libwelkin_testbase.so") << "not an ELF file";
  welkin::World w;
  w.modules().add_search_dir(dir);
  std::string e =
      error_of([&] { welkin::load_scene(w, scene_with({{"testsky.Glow", json::object()}}), "sky.json"); });
  EXPECT_NE(e.find("module 'testsky' needs module 'testbase', which cannot be loaded"), std::string::npos)
      << e;
  EXPECT_NE(e.find("cannot load module library"), std::string::npos) << e;
  EXPECT_NE(e.find("sky.json"), std::string::npos) << e;
  EXPECT_FALSE(w.modules().is_loaded("testsky"));
  EXPECT_FALSE(w.modules().is_loaded("testbase"));
  fs::remove_all(dir);
}

TEST(Plugins, AManifestNamesEachOtherModuleOnceAndNeverItself) {
  const std::string base = R"({"name": "a", "version": "1", "components": [], )";
  EXPECT_NO_THROW(welkin::parse_module_manifest(base + R"("depends": ["b"], "uses": ["c", "d"]})", "a.json"));
  EXPECT_EQ(welkin::parse_module_manifest(base + R"("uses": ["c", "d"]})", "a.json").uses,
            (std::vector<std::string>{"c", "d"}));
  for (const char* lists : {R"("depends": ["a"]})", R"("uses": ["a"]})",
                            R"("depends": ["b"], "uses": ["b"]})", R"("depends": ["b", "b"]})"}) {
    std::string e = error_of([&] { welkin::parse_module_manifest(base + lists, "a.json"); });
    EXPECT_NE(e.find("a.json: at /"), std::string::npos) << lists << ": " << e;
    EXPECT_NE(e.find("expected other modules, each named once"), std::string::npos) << lists << ": " << e;
  }
  std::string e = error_of([&] { welkin::parse_module_manifest(base + R"("uses": "b"})", "a.json"); });
  EXPECT_NE(e.find("a.json: at /uses: expected array of strings, found string"), std::string::npos) << e;
}

}  // namespace
