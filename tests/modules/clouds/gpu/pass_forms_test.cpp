// The clouds' march, temporal resolve and composite in their compute form against their fragment form
// (welkin/gfx/screen_pass.h), on llvmpipe, at 67x43 (the march at 34x22 and, upscaled temporally, at
// 17x11 or 9x6): sizes no work group of 8 x 8 divides. Both forms run one body per pixel
// (clouds/march_pixel.glsl, resolve_pixel.glsl, composite_pixel.glsl) through the same compiler: a
// frame alone (the march and the composite at one size) came out equal to the bit. Where a texture is
// read between texels (the resolve's history, the composite upsampling a moving view's march) the
// fragment form's coordinate is the interpolated v_ndc and the compute form's is computed from the
// pixel, which differ in their last bits: measured up to 0.093% of a channel. The bound is the other
// screen passes' (0.2% above 1e-4 of the frame's brightest: two half-float steps); a pixel off by one
// (a half-pixel offset, a wrong stride) fails by far more.
#include <filesystem>
#include <fstream>

#include "clouds_test_support.h"
#include "pass_forms.h"

namespace welkin::clouds {
namespace {

constexpr int kW = 67, kH = 43;

nlohmann::json scene_file(const std::string& name) {
  std::ifstream in(std::filesystem::path(WELKIN_SOURCE_DIR) / "assets/scenes" / (name + ".json"));
  return nlohmann::json::parse(in);
}

std::unique_ptr<World> world_of(const nlohmann::json& doc) {
  test::gl_context().make_current();
  auto world = std::make_unique<World>();
  world->modules().add_static(welkin::modules::atmosphere_module());
  world->modules().add_static(welkin::modules::clouds_module());
  load_scene(*world, doc, "test scene");
  return world;
}

// `frames` frames of `doc` (not alone: temporally upscaled where the clouds ask for it), the camera
// turning 1.5 degrees and flying 30 m a frame; every full-screen pass a fragment pass except those in
// `compute`. The last frame.
testing::FormFrame render_turning(const nlohmann::json& doc, const std::vector<std::string>& compute,
                                  int frames) {
  std::unique_ptr<World> world = world_of(doc);
  Renderer renderer(*world);
  renderer.context().forms.forced["*"] = PassForm::fragment;
  for (const std::string& pass : compute) renderer.context().forms.forced[pass] = PassForm::compute;
  Camera& camera = *world->registry().get<Camera>(world->registry().first<Camera>());
  const glm::dvec3 start = camera.position_m;
  FrameResult r;
  for (int f = 0; f < frames; ++f) {
    camera.heading_deg += 1.5f;
    camera.position_m = start + glm::dvec3(30.0 * f, 10.0 * f, 2.0 * f);
    r = renderer.render_frame(FrameInfo{.index = uint64_t(f)}, kW, kH);
  }
  testing::FormFrame out{renderer.read_hdr(), renderer.read_output(), {}};
  for (const auto& t : r.timings) out.passes.push_back(t.name);
  return out;
}

void expect_equal_frames(const testing::FormFrame& f, const testing::FormFrame& c, const std::string& what) {
  const testing::HdrDifference d = testing::hdr_difference(f.hdr, c.hdr, 1e-4);
  EXPECT_GT(d.brightest, 0.0) << what;
  EXPECT_LE(d.worst, 2e-3) << what << " at pixel " << d.x << "," << d.y;
  EXPECT_LE(testing::output_difference(f.output, c.output), 1) << what;
  if (d.worst > 0.0) std::printf("%s: largest relative difference %.3g\n", what.c_str(), d.worst);
}

// One frame alone (every pixel marched, no resolve): the march or the composite in compute form.
void expect_forms_agree(const nlohmann::json& doc, const std::string& pass) {
  const auto make = [&doc] { return world_of(doc); };
  const testing::FormFrame f = testing::render_with_form(make, pass, PassForm::fragment, kW, kH);
  const testing::FormFrame c = testing::render_with_form(make, pass, PassForm::compute, kW, kH);
  ASSERT_TRUE(f.ran(pass) && c.ran(pass)) << pass;
  expect_equal_frames(f, c, pass);
}

// The peer scene: cumulus around debug shapes (geometry that ends rays), high quality.
nlohmann::json peer() {
  nlohmann::json doc = scene_file("clouds-peer");
  nlohmann::json& clouds = test::entity_with(doc, "clouds.VolumetricClouds")["components"];
  clouds["clouds.VolumetricClouds"]["quality"] = "high";
  return doc;
}

TEST(CloudsPassForms, MarchAlone) { expect_forms_agree(peer(), "clouds.march"); }

TEST(CloudsPassForms, CompositeAlone) { expect_forms_agree(peer(), "clouds.composite"); }

// Seven frames turning and flying: the first marches every pixel, then one of each block a frame (and
// the pixels next to the last frame's silhouettes, listed and marched in compute whatever the form),
// the resolve reprojecting the rest. Each pass in compute form alone, then all three.
TEST(CloudsPassForms, MarchResolveCompositeTurning) {
  nlohmann::json doc = peer();
  test::entity_with(doc, "clouds.VolumetricClouds")["components"]["clouds.VolumetricClouds"]["march_silhouettes"] =
      true;
  const testing::FormFrame f = render_turning(doc, {}, 7);
  ASSERT_TRUE(f.ran("clouds.resolve"));
  ASSERT_TRUE(f.ran("clouds.silhouettes_mark"));
  ASSERT_TRUE(f.ran("clouds.march_silhouettes"));
  for (const std::string pass : {"clouds.march", "clouds.resolve", "clouds.composite"})
    expect_equal_frames(f, render_turning(doc, {pass}, 7), pass + " turning");
  expect_equal_frames(f, render_turning(doc, {"clouds.march", "clouds.resolve", "clouds.composite"}, 7),
                      "all three turning");
}

// The mesh clusters behind the march: the resolve lays them in (or the composite, where their sizes
// differ), and the march ends where they turn opaque.
TEST(CloudsPassForms, WithClustersTurning) {
  const nlohmann::json doc = scene_file("clouds-clusters");
  const testing::FormFrame f = render_turning(doc, {}, 5);
  const testing::FormFrame c =
      render_turning(doc, {"clouds.march", "clouds.resolve", "clouds.composite"}, 5);
  ASSERT_TRUE(f.ran("clouds.clusters_draw") && f.ran("clouds.march"));
  expect_equal_frames(f, c, "with clusters");
}

}  // namespace
}  // namespace welkin::clouds
