// The atmosphere's full-screen passes and the tone map in their compute form against their fragment
// form (welkin/gfx/screen_pass.h), on llvmpipe, at 67x43: a size no work group of 8 x 8 divides, so
// the last tiles overhang the frame. One frame with every full-screen pass a fragment pass, one with
// the pass under test in its compute form; the frames' colour must agree within half-float rounding.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pass_forms.h"
#include "welkin/core/module.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/screen_pass.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
}

namespace welkin::atmosphere {
namespace {

using nlohmann::json;
using testing::FormFrame;

GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

constexpr int kW = 67, kH = 43;
// A channel differs by at most two half-float steps (2^-10 of its value each) where it is above 1e-4 of
// the frame's brightest channel; the two forms compute the same arithmetic, but a view direction
// interpolated across a triangle and one computed at the pixel differ in their last float bits, and a
// value then rounds to the neighbouring half float.
constexpr double kRelative = 2e-3, kFloor = 1e-4;

// A scene of assets/scenes, changed by `edit` (its parsed JSON).
std::function<std::unique_ptr<World>()> scene(const std::string& name,
                                              const std::function<void(json&)>& edit = {}) {
  return [name, edit] {
    gl().make_current();
    std::ifstream in(std::filesystem::path(WELKIN_SOURCE_DIR) / "assets/scenes" / (name + ".json"));
    json doc = json::parse(in);
    if (edit) edit(doc);
    auto world = std::make_unique<World>();
    world->modules().add_static(modules::atmosphere_module());
    load_scene(*world, doc, name);
    return world;
  };
}

json& component(json& doc, const std::string& type) {
  for (auto& e : doc["entities"])
    if (e["components"].contains(type)) return e["components"][type];
  throw std::runtime_error("no " + type);
}

// Both forms of `pass` in a scene; the pass must have run in both. Every pixel within kRelative, or
// (`limb`) all but a fraction of them, and those within `limb_worst`.
struct Limb {
  double fraction = 0.0, worst = kRelative;
};
void expect_forms_agree(const std::function<std::unique_ptr<World>()>& make, const std::string& pass,
                        Limb limb = {}) {
  const FormFrame f = testing::render_with_form(make, pass, PassForm::fragment, kW, kH);
  const FormFrame c = testing::render_with_form(make, pass, PassForm::compute, kW, kH);
  ASSERT_TRUE(f.ran(pass) && c.ran(pass)) << pass;
  const testing::HdrDifference d = testing::hdr_difference(f.hdr, c.hdr, kFloor, kRelative);
  EXPECT_GT(d.brightest, 0.0);
  EXPECT_LE(d.worst, limb.worst) << pass << " at pixel " << d.x << "," << d.y << "; " << d.pixels_over
                                 << " pixels over";
  EXPECT_LE(d.pixels_over, int(limb.fraction * kW * kH))
      << pass << ": pixels differing by more than " << kRelative;
  // The tone map rounds both alike, give or take the step a value on a rounding boundary takes.
  EXPECT_LE(testing::output_difference(f.output, c.output), 1) << pass;
}

TEST(ScreenPassForms, ToneMap) {
  const FormFrame f =
      testing::render_with_form(scene("atmosphere-noon"), "tonemap", PassForm::fragment, kW, kH);
  const FormFrame c =
      testing::render_with_form(scene("atmosphere-noon"), "tonemap", PassForm::compute, kW, kH);
  EXPECT_EQ(testing::hdr_difference(f.hdr, c.hdr, kFloor).worst, 0.0) << "the same HDR frame";
  EXPECT_LE(testing::output_difference(f.output, c.output), 1);
}

// A moving view at half size: the tone map upscales bilinearly into the whole output.
TEST(ScreenPassForms, ToneMapUpscaling) {
  auto moving = [](PassForm form) {
    std::unique_ptr<World> world = scene(
        "atmosphere-noon", [](json& doc) { component(doc, "core.Camera")["moving_render_scale"] = 0.5; })();
    Renderer renderer(*world);
    renderer.context().forms.forced["*"] = PassForm::fragment;
    renderer.context().forms.forced["tonemap"] = form;
    renderer.render_frame(FrameInfo{.index = 0}, kW, kH);
    Registry& reg = world->registry();
    reg.get<Camera>(reg.first<Camera>())->heading_deg += 2.0f;
    const FrameResult r = renderer.render_frame(FrameInfo{.index = 1}, kW, kH);
    EXPECT_LT(r.rendered_width, kW);
    return renderer.read_output();
  };
  EXPECT_LE(testing::output_difference(moving(PassForm::fragment), moving(PassForm::compute)), 1);
}

TEST(ScreenPassForms, SkyFromTheSkyViewLutWithTheSunsDisc) {
  expect_forms_agree(scene("atmosphere-sunset"), "atmosphere.sky");
}

TEST(ScreenPassForms, SkyAtTwilightWithTheMoon) {
  expect_forms_agree(scene("atmosphere-twilight"), "atmosphere.sky");
}

// From 400 km the limb crosses the frame: there a ray's path through the air changes by orders of
// magnitude within a pixel, and the last float bits of its direction (interpolated across a triangle,
// or computed at the pixel) move where the march ends. 9 of 2881 pixels differ by more than 0.2% (the
// most by 1.5%): at most 0.5% of them, by at most 3%.
TEST(ScreenPassForms, SkyMarchedFromSpace) {
  expect_forms_agree(scene("atmosphere-orbit"), "atmosphere.sky", Limb{.fraction = 0.005, .worst = 0.03});
}

TEST(ScreenPassForms, SkyWithMethodRaymarch) {
  expect_forms_agree(scene("atmosphere-noon",
                           [](json& doc) { component(doc, "atmosphere.Atmosphere")["method"] = "raymarch"; }),
                     "atmosphere.sky");
}

TEST(ScreenPassForms, AerialPerspectiveOnTheGeometry) {
  expect_forms_agree(scene("atmosphere-noon"), "atmosphere.aerial_perspective_apply");
}

// The device's form is measured, and a forced form wins over it, for one pass or all.
TEST(ScreenPassForms, TheDevicesFormIsMeasuredAndCanBeForced) {
  gl().make_current();
  ShaderLibrary shaders;
  shaders.add_search_dir(runtime_shader_dir());
  const PassFormProbe p = probe_pass_form(shaders, 67, 43, 3);
  EXPECT_GT(p.fragment_ms, 0.0);
  EXPECT_GT(p.compute_ms, 0.0);
  EXPECT_EQ(p.chosen, p.compute_ms <= 0.5 * p.fragment_ms ? PassForm::compute : PassForm::fragment);
  PassForms forms{.device = PassForm::compute, .measured = true};
  EXPECT_TRUE(forms.compute("atmosphere.sky"));
  forms.forced["*"] = PassForm::fragment;
  forms.forced["tonemap"] = PassForm::compute;
  EXPECT_FALSE(forms.compute("atmosphere.sky"));
  EXPECT_TRUE(forms.compute("tonemap"));
}

}  // namespace
}  // namespace welkin::atmosphere
