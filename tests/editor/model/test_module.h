#pragma once
// A small static module for the editor model tests: components with every kind of field the
// inspector, presets and timeline handle (ints, enums, colours, arrays of structs, strings), whose
// preset folder is a scratch directory each test fills.
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <memory>
#include <string>
#include <vector>

#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "scratch_folder.h"

namespace editor_test {

struct CloudLayer {
  static constexpr std::string_view kTypeName = "test.CloudLayer";
  float coverage = 0.5f;
  int octaves = 4;
};
inline void describe(welkin::TypeBuilder<CloudLayer>& t) {
  t.field("coverage", &CloudLayer::coverage).range(0, 1);
  t.field("octaves", &CloudLayer::octaves).range(1, 8);
}

enum class CloudMode : int { fast = 0, precise = 1 };

struct Clouds {
  static constexpr std::string_view kTypeName = "test.Clouds";
  float density = 1.0f;
  int steps = 16;
  double altitude_m = 1500.0;
  CloudMode mode = CloudMode::fast;
  glm::vec3 tint{1.0f, 1.0f, 1.0f};
  bool shadows = true;
  std::string label = "cumulus";
  std::vector<CloudLayer> layers{CloudLayer{}};
};
inline void describe(welkin::TypeBuilder<Clouds>& t) {
  t.field("density", &Clouds::density).unit("1/km").range(0, 100).tooltip("Extinction");
  t.field("steps", &Clouds::steps).range(1, 256);
  t.field("altitude_m", &Clouds::altitude_m).unit("m").range(0, 20000);
  t.field("mode", &Clouds::mode).values({{"fast", 0}, {"precise", 1}});
  t.field("tint", &Clouds::tint).color().range(0, 1);
  t.field("shadows", &Clouds::shadows);
  t.field("label", &Clouds::label);
  t.field("layers", &Clouds::layers).max_count(4);
}

struct Fog {
  static constexpr std::string_view kTypeName = "test.Fog";
  float visibility_km = 10.0f;
};
inline void describe(welkin::TypeBuilder<Fog>& t) { t.field("visibility_km", &Fog::visibility_km).unit("km").range(0.01, 1000); }

// Names a map painted over the planet, as clouds.VolumetricClouds does its coverage map.
struct Weather {
  static constexpr std::string_view kTypeName = "test.Weather";
  std::string map;
  double map_size_m = 20000.0;
};
inline void describe(welkin::TypeBuilder<Weather>& t) {
  t.field("map", &Weather::map);
  t.field("map_size_m", &Weather::map_size_m).unit("m").range(100, 1e7);
}

// The module's data folder (presets/ inside it); set before the first world is made.
inline std::string& test_module_data_dir() {
  static std::string dir;
  return dir;
}

inline void register_test_module(welkin::ModuleContext& ctx) {
  ctx.component<Clouds>();
  ctx.component<Fog>();
  ctx.component<Weather>();
}

inline const welkin::ModuleDefinition& test_module() {
  static welkin::ModuleDefinition def{
      R"({"name": "test", "version": "1.0.0", "components": ["test.Clouds", "test.Fog", "test.Weather"]})", nullptr, register_test_module};
  def.data_dir = test_module_data_dir().c_str();
  return def;
}

inline std::unique_ptr<welkin::World> make_test_world() {
  auto world = std::make_unique<welkin::World>();
  world->modules().add_static(test_module());
  return world;
}

// A fresh scratch folder per test, removed afterwards.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(welkin::testing::scratch_folder("welkin-editor-test") / name) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& relative, const std::string& text) const {
    std::filesystem::path p = path_ / relative;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace editor_test
