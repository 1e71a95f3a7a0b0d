// The light environment: how terms compose into welkin/lighting.glsl and where their resources go
// (no GL), and, on llvmpipe, that a term declared by code outside the runtime changes what every
// material receives through the units the environment assigned.
#include "welkin/gfx/light_environment.h"

#include <gtest/gtest.h>

#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/scene_file.h"

namespace {

using namespace welkin;

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST(LightEnvironment, HighestPriorityLightsWinAndOnlyUsedTermsAreIncluded) {
  LightEnvironment env;
  env.add({.name = "base", .include = "base.glsl", .lights = "base", .priority = 0});
  env.add({.name = "sky", .include = "sky.glsl", .lights = "sky", .priority = 10, .aerial_perspective = "sky_ap"});
  const std::string s = env.composed_source();
  EXPECT_EQ(count(s, "#include \"sky.glsl\""), 1u);
  EXPECT_EQ(count(s, "base.glsl"), 0u) << "a provider that lost to another must compile nothing";
  EXPECT_NE(s.find("return sky_sun_irradiance(p);"), std::string::npos);
  EXPECT_NE(s.find("return sky_ap(p, transmittance);"), std::string::npos);
}

TEST(LightEnvironment, VisibilitiesMultiplyAndTermsComeAndGo) {
  LightEnvironment env;
  env.add({.name = "a", .include = "a.glsl", .light_visibility = "a_vis"});
  env.add({.name = "b", .include = "b.glsl", .light_visibility = "b_vis", .sky_visibility = "b_sky", .added_irradiance = "b_add"});
  std::string s = env.composed_source();
  EXPECT_NE(s.find("v *= a_vis(p, n, light);\n  v *= b_vis(p, n, light);"), std::string::npos) << s;
  EXPECT_NE(s.find("v *= b_sky(p, n);"), std::string::npos);
  EXPECT_NE(s.find("e += b_add(p, n);"), std::string::npos);
  const uint64_t v = env.version();
  EXPECT_TRUE(env.remove("b"));
  EXPECT_GT(env.version(), v);
  s = env.composed_source();
  EXPECT_EQ(s.find("b_vis"), std::string::npos);
  EXPECT_EQ(s.find("b.glsl"), std::string::npos);
  // No lights at all: materials still compile, and receive nothing.
  EXPECT_NE(s.find("vec3 welkin_sun_irradiance(vec3 p) { return vec3(0.0); }"), std::string::npos);
}

// welkin_surface_light asks each term once: a term naming a surface function through it alone, the
// others through their three functions (the moon's visibility only while the moon lights surfaces).
TEST(LightEnvironment, SurfaceLightAsksEachTermOnce) {
  LightEnvironment env;
  env.add({.name = "a", .include = "a.glsl", .light_visibility = "a_vis", .sky_visibility = "a_sky"});
  env.add({.name = "b", .include = "b.glsl", .light_visibility = "b_vis", .sky_visibility = "b_sky",
           .added_irradiance = "b_add", .surface_light = "b_surface"});
  const std::string s = env.composed_source();
  const size_t at = s.find("WelkinSurfaceLight welkin_surface_light(vec3 p, vec3 n) {");
  ASSERT_NE(at, std::string::npos) << s;
  const std::string body = s.substr(at, s.find("\n}\n", at) - at);
  EXPECT_NE(body.find("WelkinSurfaceLight(welkin_sun_irradiance(p), 1.0, 1.0, 1.0, vec3(0.0))"), std::string::npos) << body;
  EXPECT_EQ(count(body, "a_vis(p, n, 0)"), 1u) << body;
  EXPECT_NE(body.find("#if WELKIN_MOON_LIGHT\n  l.moon_visibility *= a_vis(p, n, 1);\n#endif"), std::string::npos) << body;
  EXPECT_EQ(count(body, "a_sky(p, n)"), 1u);
  EXPECT_EQ(count(body, "b_surface(p, n, l);"), 1u);
  EXPECT_EQ(body.find("b_vis"), std::string::npos) << "b's three are asked through its surface function";
  EXPECT_EQ(body.find("b_sky"), std::string::npos);
  EXPECT_EQ(body.find("b_add"), std::string::npos);
  // The three stay for what samples one of them alone (a march through shadowed air).
  EXPECT_NE(s.find("v *= b_vis(p, n, light);"), std::string::npos);
  EXPECT_LT(s.find("struct WelkinSurfaceLight"), s.find("#include \"a.glsl\"")) << "terms may name the struct";
  // A term with a surface function alone is included and shades surfaces.
  LightEnvironment only;
  only.add({.name = "c", .include = "c.glsl", .surface_light = "c_surface"});
  EXPECT_TRUE(only.shades_surfaces());
  EXPECT_NE(only.composed_source().find("#include \"c.glsl\""), std::string::npos);
}

// The environment's state follows every term's, and the composed source; a term that reports none
// leaves the environment without one (nothing may then be kept between frames). The moon's switch
// is in the composed source.
TEST(LightEnvironment, StateFollowsEveryTermAndTheSource) {
  LightEnvironment env;
  uint64_t a = 1, b = 2;
  env.add({.name = "a", .include = "a.glsl", .lights = "a", .state = [&a] { return a; }});
  env.add({.name = "b", .include = "b.glsl", .light_visibility = "b_vis", .state = [&b] { return b; }});
  const std::optional<uint64_t> first = env.state();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(env.state(), first) << "nothing changed";
  b = 3;
  const std::optional<uint64_t> second = env.state();
  EXPECT_NE(second, first);
  EXPECT_NE(env.composed_source().find("#define WELKIN_MOON_LIGHT 1"), std::string::npos);
  env.set_moon_lights_surfaces(false);
  EXPECT_NE(env.composed_source().find("#define WELKIN_MOON_LIGHT 0"), std::string::npos);
  EXPECT_NE(env.state(), second) << "the composed source changed";
  env.add({.name = "c", .include = "c.glsl", .sky_visibility = "c_vis"});
  EXPECT_FALSE(env.state().has_value());
}

TEST(LightEnvironment, BindingsAreAssignedOnceAndNeverMove) {
  LightEnvironment env;
  env.add({.name = "a", .textures = {"a.lut", "a.map"}, .blocks = {"a"}});
  env.add({.name = "b", .textures = {"b.map"}, .blocks = {"b"}});
  EXPECT_EQ(env.unit("a.lut"), LightEnvironment::kFirstUnit);
  EXPECT_EQ(env.unit("a.map"), LightEnvironment::kFirstUnit + 1);
  EXPECT_EQ(env.unit("b.map"), LightEnvironment::kFirstUnit + 2);
  EXPECT_EQ(env.block("b"), LightEnvironment::kFirstBlock + 1);
  env.add({.name = "a", .textures = {"a.lut", "a.map"}, .blocks = {"a"}});  // replaced: same units
  env.remove("a");
  EXPECT_EQ(env.unit("b.map"), LightEnvironment::kFirstUnit + 2);
  const ShaderDefines d = env.binding_defines();
  EXPECT_EQ(d.at("WELKIN_UNIT_B_MAP"), std::to_string(LightEnvironment::kFirstUnit + 2));
  EXPECT_EQ(d.at("WELKIN_BLOCK_A"), std::to_string(LightEnvironment::kFirstBlock));
  EXPECT_THROW(env.unit("c.map"), Error);
  // Another term may not take a name that is already bound.
  EXPECT_THROW(env.add({.name = "c", .textures = {"b.map"}}), Error);
}

TEST(LightEnvironment, RunsOutOfUnitsWithAClearError) {
  LightEnvironment env;
  std::vector<std::string> many;
  for (int i = 0; i < 100; ++i) many.push_back("t" + std::to_string(i));
  try {
    env.add({.name = "greedy", .textures = many});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ran out of bindings"), std::string::npos) << e.what();
  }
}

class LightEnvironmentGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = create_headless_context().release(); }
  static void TearDownTestSuite() { delete context_; }
  static GlContext* context_;
};
GlContext* LightEnvironmentGl::context_ = nullptr;

// Linear HDR of the debug scene, optionally with the test term scaling sun and sky.
ImageF render_debug_scene(float sun_scale, float sky_scale, bool with_term, std::string* lighting = nullptr) {
  World world;
  load_scene_file(world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  Renderer r(world);
  r.context().shaders.add_search_dir(WELKIN_SOURCE_DIR "/tests/runtime/gfx/shaders");
  std::shared_ptr<Texture> shade;
  std::shared_ptr<Buffer> sky;
  if (with_term) {
    shade = std::make_shared<Texture>(TextureDesc{.width = 1, .height = 1, .format = TextureFormat::rgba32f, .linear_filter = false});
    const float texel[4] = {sun_scale, 0, 0, 1};
    glTextureSubImage2D(shade->id(), 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, texel);
    const float block[4] = {sky_scale, 0, 0, 0};
    sky = std::make_shared<Buffer>(sizeof(block), block);
    world.resource<LightEnvironment>().add(LightTerm{
        .name = "test",
        .include = "test/light_term.glsl",
        .light_visibility = "test_light_visibility",
        .sky_visibility = "test_sky_visibility",
        .textures = {"test.shade"},
        .blocks = {"test.sky"},
        .bind = [shade, sky](const LightEnvironment& env) {
          glBindTextureUnit(env.unit("test.shade"), shade->id());
          glBindBufferBase(GL_UNIFORM_BUFFER, env.block("test.sky"), sky->id());
        }});
  }
  r.render_frame({}, 64, 36);
  if (lighting) *lighting = r.context().shaders.preprocess("debug_shape.frag", {}).text;
  return r.read_hdr();
}

TEST_F(LightEnvironmentGl, ATermDeclaredOutsideTheRuntimeScalesEveryMaterial) {
  std::string plain_source, term_source;
  const ImageF plain = render_debug_scene(1, 1, false, &plain_source);
  const ImageF halved = render_debug_scene(0.5f, 0.5f, true, &term_source);
  const ImageF dark = render_debug_scene(0, 0, true);
  EXPECT_EQ(plain_source.find("test_light_visibility"), std::string::npos);
  EXPECT_NE(term_source.find("test_light_visibility"), std::string::npos);
  // The backdrop is not a material (no lights): identical. Lit shapes: exactly scaled.
  int shape_pixels = 0;
  for (size_t i = 0; i < plain.rgba.size(); i += 4) {
    const bool shape = std::abs(dark.rgba[i] - plain.rgba[i]) > 1e-3f * plain.rgba[i];
    if (!shape) continue;
    ++shape_pixels;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(dark.rgba[i + c], 0.0f, 1e-6f);
      EXPECT_NEAR(halved.rgba[i + c], 0.5f * plain.rgba[i + c], 2e-3f * plain.rgba[i + c] + 1e-6f);
    }
  }
  EXPECT_GT(shape_pixels, 40);
}

}  // namespace
