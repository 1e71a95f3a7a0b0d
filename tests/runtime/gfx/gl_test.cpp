// Headless GL on llvmpipe (EGL surfaceless): exact readback, shader includes and errors, images,
// and a golden image of the built-in debug scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "golden.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/shader.h"
#include "welkin/scene/scene_file.h"

namespace {

using namespace welkin;

class Gl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = create_headless_context().release(); }
  static void TearDownTestSuite() { delete context_; }
  static GlContext* context_;
};
GlContext* Gl::context_ = nullptr;

const char* kTestShaders = WELKIN_SOURCE_DIR "/tests/runtime/gfx/shaders";

TEST_F(Gl, ContextIsOpenGl45Core) {
  GlInfo i = context_->info();
  EXPECT_NE(i.version.find("4.5"), std::string::npos) << i.version;
}

TEST_F(Gl, RendersAKnownPatternAndReadsItBackExactly) {
  ShaderLibrary lib;
  lib.add_search_dir(kTestShaders);
  lib.add_search_dir(runtime_shader_dir());
  const Program& p = lib.graphics("fullscreen.vert", "pattern.frag", {{"PATTERN_ALPHA", "200"}});
  Texture target(TextureDesc{.width = 37, .height = 19, .format = TextureFormat::rgba8});
  Framebuffer fb(&target, nullptr);
  fb.bind();
  p.use();
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDeleteVertexArrays(1, &vao);
  ImageU8 img = read_texture_rgba8(target);
  ASSERT_EQ(img.width, 37);
  int mismatches = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      int gy = img.height - 1 - y;  // image rows are top-down, GL's bottom-up
      const uint8_t* px = img.pixel(x, y);
      mismatches += px[0] != ((x * 7 + gy) & 255) || px[1] != ((gy * 13) & 255) || px[2] != ((x ^ gy) & 255) || px[3] != 200;
    }
  EXPECT_EQ(mismatches, 0);
}

TEST_F(Gl, ShaderErrorsNameTheRealFileAndLine) {
  ShaderLibrary lib;
  lib.add_search_dir(kTestShaders);
  lib.add_search_dir(runtime_shader_dir());
  try {
    lib.graphics("fullscreen.vert", "broken.frag", {{"PATTERN_ALPHA", "1"}});
    FAIL() << "broken shader compiled";
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("broken.frag:5:"), std::string::npos) << m;
  }
  try {
    lib.graphics("fullscreen.vert", "missing.frag");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.frag: shader not found"), std::string::npos) << e.what();
  }
}

TEST_F(Gl, IncludesExpandOnceWithLineDirectives) {
  ShaderLibrary lib;
  lib.add_search_dir(kTestShaders);
  ShaderSource s = lib.preprocess("pattern.frag", {{"PATTERN_ALPHA", "3"}});
  EXPECT_EQ(s.text.rfind("#version 450 core\n", 0), 0u);
  EXPECT_NE(s.text.find("#define PATTERN_ALPHA 3"), std::string::npos);
  ASSERT_EQ(s.files.size(), 2u);
  EXPECT_NE(s.text.find("#line 2 0"), std::string::npos) << "back in the includer after the include";
}

TEST_F(Gl, ExrRoundTripPreservesHdrValues) {
  ImageF img{3, 2, {}};
  for (int i = 0; i < 6; ++i) {
    float v[4] = {float(i) * 1000.5f, 1e-3f * float(i + 1), 65000.0f, 1.0f};
    img.rgba.insert(img.rgba.end(), v, v + 4);
  }
  auto path = std::filesystem::temp_directory_path() / "welkin-roundtrip.exr";
  write_exr(path.string(), img, ExrPrecision::full);
  ImageF back = read_exr(path.string());
  EXPECT_EQ(back.rgba, img.rgba);
  write_exr(path.string(), img, ExrPrecision::half);
  back = read_exr(path.string());
  for (size_t i = 0; i < img.rgba.size(); ++i) EXPECT_NEAR(back.rgba[i], img.rgba[i], std::abs(img.rgba[i]) * 1e-3);
}

// The shader's sRGB encode is a fit in square roots (tonemap.glsl): over 4096 linear values it rounds
// to the exact curve's 8-bit value or the next one, and to the same one for nearly all.
TEST_F(Gl, ShaderSrgbEncodeRoundsLikeTheExactCurve) {
  ShaderLibrary lib;
  lib.add_search_dir(kTestShaders);
  lib.add_search_dir(runtime_shader_dir());
  const int width = 4096;
  const Program& p = lib.graphics("fullscreen.vert", "srgb_ramp.frag");
  Texture target(TextureDesc{.width = width, .height = 1, .format = TextureFormat::rgba8});
  Framebuffer fb(&target, nullptr);
  fb.bind();
  p.use();
  p.set("u_width", width);
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDeleteVertexArrays(1, &vao);
  const ImageU8 img = read_texture_rgba8(target);
  int off_by_one = 0;
  for (int x = 0; x < width; ++x) {
    const float c = float(x) / float(width - 1);
    const int exact = linear_to_srgb8(c), got = img.pixel(x, 0)[0];
    ASSERT_LE(std::abs(got - exact), 1) << "linear " << c;
    off_by_one += got != exact;
  }
  EXPECT_LT(off_by_one, width / 50) << "values that round to the neighbouring step";
}

TEST(Srgb, TransferFunctionMatchesTheStandard) {
  EXPECT_EQ(linear_to_srgb8(0.0f), 0);
  EXPECT_EQ(linear_to_srgb8(1.0f), 255);
  EXPECT_EQ(linear_to_srgb8(0.5f), 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(linear_to_srgb8(0.0031308f), 10);
  for (int v = 0; v < 256; ++v) EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(uint8_t(v))), v);
}

TEST_F(Gl, DebugSceneMatchesGolden) {
  World world;
  load_scene_file(world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  Renderer r(world);
  FrameResult fr = r.render_frame({}, 160, 90);
  std::vector<std::string> passes;
  for (const auto& t : fr.timings) passes.push_back(t.name);
  EXPECT_EQ(passes, (std::vector<std::string>{"clear", "backdrop", "debug_shapes", "tonemap"}));
  auto res = welkin::testing::compare_with_golden(r.read_output(), "runtime/debug_scene", {.max_channel_difference = 6, .max_failing_fraction = 0.003});
  EXPECT_TRUE(res.passed) << res.message;
}

// Each tone curve is its own shader variant: the linear one is exactly the clamped sRGB encoding of
// the exposed HDR frame (to the byte), and the three curves give three different images.
TEST_F(Gl, EachToneCurveIsItsOwnVariant) {
  World world;
  load_scene_file(world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  Renderer r(world);
  Registry& reg = world.registry();
  Camera& camera = *reg.get<Camera>(reg.first<Camera>());
  camera.exposure_mode = ExposureMode::manual, camera.exposure = 3e-5f;
  std::vector<ImageU8> outputs;
  for (Tonemapper t : {Tonemapper::aces, Tonemapper::agx, Tonemapper::linear}) {
    camera.tonemapper = t;
    r.render_frame({}, 64, 36);
    outputs.push_back(r.read_output());
  }
  const ImageF hdr = r.read_hdr();
  int off = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        const int expected = linear_to_srgb8(std::clamp(hdr.pixel(x, y)[c] * 3e-5f, 0.0f, 1.0f));
        off += std::abs(int(outputs[2].pixel(x, y)[c]) - expected) > 1;
      }
  EXPECT_EQ(off, 0);
  EXPECT_NE(outputs[0].rgba, outputs[1].rgba);
  EXPECT_NE(outputs[0].rgba, outputs[2].rgba);
  EXPECT_NE(outputs[1].rgba, outputs[2].rgba);
}

TEST_F(Gl, SceneWithoutCameraIsAClearError) {
  World world;
  Renderer r(world);
  try {
    r.render_frame({}, 8, 8);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no camera"), std::string::npos);
  }
}

}  // namespace
