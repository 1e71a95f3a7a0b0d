// The atmosphere scenes (assets/scenes/atmosphere-*.json) rendered headless at 96x54 against golden
// images: noon, sunset, civil twilight (sun at -6 degrees) and the planet from 400 km. Each scene is
// checked to be what its name says before its image is compared.
#include "golden.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "welkin/atmosphere/components.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
}

namespace welkin::atmosphere {
namespace {

GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

struct Scene {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
  const Sun& sun() { return *world->registry().get<Sun>(world->registry().first<Sun>()); }
  const Camera& camera() { return *world->registry().get<Camera>(world->registry().first<Camera>()); }
};

Scene load(const std::string& name) {
  gl().make_current();
  Scene s{std::make_unique<World>(), nullptr};
  s.world->modules().add_static(welkin::modules::atmosphere_module());
  load_scene_file(*s.world,
                  (std::filesystem::path(WELKIN_SOURCE_DIR) / "assets/scenes" / (name + ".json")).string());
  s.renderer = std::make_unique<Renderer>(*s.world);
  return s;
}

// llvmpipe renders these bit for bit from run to run; the tolerance absorbs a different LLVM or Mesa
// (rounding in the LUTs' exp and the tone curve): 4 levels per 8-bit channel on 0.5% of the pixels.
constexpr testing::GoldenTolerance kTolerance{.max_channel_difference = 4, .max_failing_fraction = 0.005};

void expect_golden(Scene& s, const std::string& name) {
  s.renderer->render_frame(FrameInfo{}, 96, 54);
  // The helper writes failures to golden-output/<name>.*.png without creating the subfolder.
  std::filesystem::create_directories(std::filesystem::path(WELKIN_BINARY_DIR) / "golden-output/atmosphere");
  const testing::GoldenResult r =
      testing::compare_with_golden(s.renderer->read_output(), "atmosphere/" + name, kTolerance);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(AtmosphereGolden, Noon) {
  Scene s = load("atmosphere-noon");
  EXPECT_GE(s.sun().elevation_deg, 45.0f);
  expect_golden(s, "noon");
}

TEST(AtmosphereGolden, Sunset) {
  Scene s = load("atmosphere-sunset");
  EXPECT_GE(s.sun().elevation_deg, 0.0f);
  EXPECT_LE(s.sun().elevation_deg, 3.0f);
  expect_golden(s, "sunset");
}

TEST(AtmosphereGolden, CivilTwilight) {
  Scene s = load("atmosphere-twilight");
  EXPECT_EQ(s.sun().elevation_deg, -6.0f);
  expect_golden(s, "twilight");
}

TEST(AtmosphereGolden, OrbitAt400Km) {
  Scene s = load("atmosphere-orbit");
  EXPECT_EQ(s.camera().position_m.z, 400000.0);
  expect_golden(s, "orbit");
}

}  // namespace
}  // namespace welkin::atmosphere
