// Headless GL on llvmpipe (EGL surfaceless): exact readback, shader includes and errors, images,
// and a golden image of the built-in debug scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "depth_readback.h"
#include "golden.h"
#include "welkin/core/error.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/shader.h"
#include "welkin/scene/scene_file.h"
#include "scratch_folder.h"

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
  auto path = welkin::testing::scratch_folder("welkin-gl-test") / "roundtrip.exr";
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

// A moving view renders at the camera's moving_render_scale and its output is that frame read
// bilinearly at each output pixel's centre (against a CPU bilinear read of the HDR frame, to one step
// of 8 bits); a still view, a frame rendered alone and a scale of 1 render whole, the still frame bit
// for bit what a fresh renderer draws.
TEST_F(Gl, MovingViewRendersAtItsScaleAndIsUpscaled) {
  auto debug_world = [](World& world) {
    load_scene_file(world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
    Registry& reg = world.registry();
    Camera& camera = *reg.get<Camera>(reg.first<Camera>());
    camera.exposure_mode = ExposureMode::manual, camera.exposure = 3e-5f, camera.tonemapper = Tonemapper::linear;
    camera.moving_render_scale = 0.5f;
    return &camera;
  };
  World world;
  Camera& camera = *debug_world(world);
  Renderer r(world);
  EXPECT_EQ(r.render_frame({.index = 1}, 64, 36).rendered_width, 64) << "no earlier view: whole";
  camera.heading_deg += 1.0f;
  const FrameResult moving = r.render_frame({.index = 2}, 64, 36);
  EXPECT_EQ(moving.rendered_width, 32);
  EXPECT_EQ(moving.rendered_height, 18);
  const ImageF hdr = r.read_hdr();
  const ImageU8 out = r.read_output();
  ASSERT_EQ(hdr.width, 32);
  ASSERT_EQ(out.width, 64);
  ASSERT_EQ(out.height, 36);
  int off = 0, edges = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      // The output pixel's centre in the HDR frame's texels (rows top-down in both), clamped at the edges.
      const double px = (x + 0.5) * 32.0 / 64.0 - 0.5, py = (y + 0.5) * 18.0 / 36.0 - 0.5;
      const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
      const double fx = px - x0, fy = py - y0;
      auto at = [&](int i, int j, int c) { return double(hdr.pixel(std::clamp(i, 0, 31), std::clamp(j, 0, 17))[c]); };
      for (int c = 0; c < 3; ++c) {
        const double v = (at(x0, y0, c) * (1 - fx) + at(x0 + 1, y0, c) * fx) * (1 - fy) + (at(x0, y0 + 1, c) * (1 - fx) + at(x0 + 1, y0 + 1, c) * fx) * fy;
        const int expected = linear_to_srgb8(std::clamp(float(v * 3e-5), 0.0f, 1.0f));
        off += std::abs(int(out.pixel(x, y)[c]) - expected) > 1;
        edges += std::abs(int(out.pixel(x, y)[c]) - int(linear_to_srgb8(std::clamp(float(at(x / 2, y / 2, c) * 3e-5), 0.0f, 1.0f)))) > 1;
      }
    }
  EXPECT_EQ(off, 0);
  EXPECT_GT(edges, 50) << "bilinear, not the nearest texel: the two differ across the shapes' edges";

  // Still: whole, the same bytes as a fresh renderer's frame of this view.
  EXPECT_EQ(r.render_frame({.index = 3}, 64, 36).rendered_width, 64);
  World fresh_world;
  Camera& fresh_camera = *debug_world(fresh_world);
  fresh_camera.heading_deg = camera.heading_deg;
  Renderer fresh(fresh_world);
  fresh.render_frame({.index = 1}, 64, 36);
  EXPECT_EQ(r.read_output().rgba, fresh.read_output().rgba);
  // Alone (`welkin render`, sequences) or at scale 1: whole while moving too.
  camera.heading_deg += 1.0f;
  EXPECT_EQ(r.render_frame({.index = 4, .alone = true}, 64, 36).rendered_width, 64);
  camera.heading_deg += 1.0f;
  camera.moving_render_scale = 1.0f;
  EXPECT_EQ(r.render_frame({.index = 5}, 64, 36).rendered_width, 64);
  camera.moving_render_scale = 0.25f;
  camera.position_m.x += 1.0;  // moving without turning
  const FrameResult quarter = r.render_frame({.index = 6}, 64, 36);
  EXPECT_EQ(quarter.rendered_width, 16);
  EXPECT_EQ(quarter.rendered_height, 9);
}

// The rectangle a box can cover holds the projection of every point of the box in front of the near
// plane (points on its corners, edges and faces, and inside), cut to the frame; boxes behind the
// camera give nothing, one around the camera the whole frame.
TEST(ScreenRect, HoldsEveryPointOfTheBoxInFrontOfTheNearPlane) {
  Camera c;
  c.heading_deg = 20, c.pitch_deg = -10, c.vertical_fov_deg = 50, c.near_m = 0.5f;
  const FrameView view = make_frame_view(c, 160, 90);
  uint32_t state = 12345;
  auto uniform = [&state](float lo, float hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * float(state >> 8) / float(1u << 24);
  };
  int tested = 0, cut = 0;
  for (int box = 0; box < 400; ++box) {
    const glm::vec3 centre(uniform(-60, 60), uniform(-20, 80), uniform(-30, 30));
    const glm::vec3 half(uniform(0.1f, 25), uniform(0.1f, 25), uniform(0.1f, 25));
    const PixelRect r = screen_rect(view, centre - half, centre + half);
    ASSERT_LE(r.x1, 160);
    ASSERT_LE(r.y1, 90);
    ASSERT_GE(r.x0, 0);
    ASSERT_GE(r.y0, 0);
    bool any_in_front = false;
    for (int k = 0; k < 2000; ++k) {
      // Corners, edges and faces are where the extremes lie: pull samples onto them.
      glm::vec3 f(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      for (int a = 0; a < 3; ++a)
        if (k % 4 > a) f[a] = f[a] < 0 ? -1.0f : 1.0f;
      const glm::vec4 clip = view.view_projection * glm::vec4(centre + half * f, 1.0f);
      if (clip.w < view.near_m) continue;
      any_in_front = true;
      const double px = (0.5 * clip.x / clip.w + 0.5) * 160, py = (0.5 * clip.y / clip.w + 0.5) * 90;
      if (px < 0 || py < 0 || px >= 160 || py >= 90) continue;
      ++tested;
      ASSERT_FALSE(r.empty()) << "box " << box;
      ASSERT_GE(px, r.x0) << "box " << box;
      ASSERT_LT(px, r.x1) << "box " << box;
      ASSERT_GE(py, r.y0) << "box " << box;
      ASSERT_LT(py, r.y1) << "box " << box;
    }
    if (!any_in_front) EXPECT_TRUE(r.empty()) << "box " << box << " is behind the near plane";
    cut += !r.empty() && !r.covers(160, 90);
  }
  EXPECT_GT(tested, 100000);
  EXPECT_GT(cut, 100);  // most boxes get less than the whole frame
  // Wholly behind the camera: nothing. Around the camera: everything.
  EXPECT_TRUE(screen_rect(view, view.forward * -10.0f - glm::vec3(1), view.forward * -10.0f + glm::vec3(1)).empty());
  EXPECT_TRUE(screen_rect(view, glm::vec3(-1), glm::vec3(1)).covers(160, 90));
  // A unit cube 10 m ahead: its rectangle is within two pixels of its corners' projection.
  const glm::vec3 ahead = view.forward * 10.0f;
  const PixelRect r = screen_rect(view, ahead - glm::vec3(0.5f), ahead + glm::vec3(0.5f));
  float lo_x = 1e9f, hi_x = -1e9f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner = ahead + glm::vec3(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
    const glm::vec4 clip = view.view_projection * glm::vec4(corner, 1.0f);
    const float px = (0.5f * clip.x / clip.w + 0.5f) * 160;
    lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px);
  }
  EXPECT_GE(float(r.x0), lo_x - 2.0f);
  EXPECT_LE(float(r.x1), hi_x + 2.0f);
}

// FrameTargets::geometry, as the debug shapes report it, holds every pixel they wrote depth to (the
// aerial perspective is applied inside it only).
TEST_F(Gl, GeometryRectangleHoldsEveryPixelWithDepth) {
  World world;
  load_scene_file(world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
  auto depth = welkin::testing::read_depth_after_geometry(world);
  Renderer r(world);
  const FrameResult fr = r.render_frame({}, 160, 90);
  ASSERT_EQ(depth->depth.size(), size_t(160 * 90));
  EXPECT_EQ(depth->outside(fr.geometry), 0);
  EXPECT_GT(depth->covered(), 200);
  // And it is not the whole frame: the ball and the crate lie in a band near the horizon.
  const int area = (fr.geometry.x1 - fr.geometry.x0) * (fr.geometry.y1 - fr.geometry.y0);
  EXPECT_LT(area, 160 * 90 / 2);
  EXPECT_LT(area, 4 * depth->covered());
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
