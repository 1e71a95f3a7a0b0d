// Welkin inside a host program (welkin/host/sky.h): the host's matrices read back as Welkin's view,
// both depth conventions, bad targets, and the host's GL state as it left it after Welkin's calls.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/host/sky.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
const ModuleDefinition& godrays_module();
const ModuleDefinition& terrain_module();
const ModuleDefinition& timeofday_module();
}  // namespace welkin::modules

namespace {

using namespace welkin;
using namespace welkin::host;
using nlohmann::json;

// --- The host's matrices (no GL) -----------------------------------------------------------------

glm::dmat4 look(const glm::dvec3& eye, const glm::dvec3& at) {
  return glm::lookAt(eye, at, glm::dvec3(0, 0, 1));
}

glm::mat4 reversed_infinite(float fov, float aspect, float near) {
  const float f = 1.0f / std::tan(0.5f * fov);
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect, p[1][1] = f, p[2][3] = -1.0f, p[3][2] = near;
  return p;
}

// A point at `distance` along the view axis, projected by `p`, read back through depth_terms.
double distance_back(const glm::mat4& p, double distance, DepthConvention c) {
  const glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -float(distance), 1.0f);
  const double ndc = clip.z / clip.w;
  const double depth = c == DepthConvention::forward ? 0.5 * ndc + 0.5 : ndc;  // what the depth buffer holds
  const glm::vec2 t = depth_terms(p);
  const double back_ndc = c == DepthConvention::forward ? 2.0 * depth - 1.0 : depth;
  return t.y / (back_ndc + t.x);
}

TEST(HostView, DepthOfBothConventionsTurnsBackIntoDistance) {
  const glm::mat4 forward = glm::perspective(1.0f, 1.5f, 0.5f, 20000.0f);
  const glm::mat4 reversed = reversed_infinite(1.0f, 1.5f, 0.5f);
  for (double d : {0.5, 1.0, 37.0, 1000.0, 15000.0}) {
    EXPECT_NEAR(distance_back(reversed, d, DepthConvention::reversed), d, d * 1e-6) << d;
    // Forward depth's floats crowd toward 1: the distance holds to what float rounding of z/w leaves.
    EXPECT_NEAR(distance_back(forward, d, DepthConvention::forward), d, d * d * 2e-6 + 1e-6) << d;
  }
}

TEST(HostView, ViewAndProjectionBecomeWelkinsView) {
  const glm::dvec3 eye(1000.0, -2000.0, 350.0), at(1000.0 + 30.0, -2000.0 + 40.0, 350.0);
  const glm::mat4 p = glm::perspective(glm::radians(50.0f), 2.0f, 0.25f, 5000.0f);
  const Camera cam{.ev100 = 12.0f, .tonemapper = Tonemapper::agx};
  const FrameView v = frame_view_of(
      View{.view = look(eye, at), .projection = p, .depth = DepthConvention::forward}, 200, 100, cam);
  EXPECT_NEAR(glm::distance(v.camera_position_m, eye), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(glm::dvec3(v.forward), glm::dvec3(0.6, 0.8, 0.0)), 0.0, 1e-6);
  EXPECT_NEAR(glm::distance(glm::dvec3(v.up), glm::dvec3(0.0, 0.0, 1.0)), 0.0, 1e-6);
  EXPECT_NEAR(v.vertical_fov_rad, glm::radians(50.0f), 1e-6);
  EXPECT_NEAR(v.near_m, 0.25, 1e-6);
  EXPECT_FLOAT_EQ(v.exposure, exposure_from_ev100(12.0f));
  EXPECT_EQ(v.tonemapper, Tonemapper::agx);
  // The reversed infinite projection of the same frustum gives the same view.
  const FrameView r = frame_view_of(
      View{.view = look(eye, at), .projection = reversed_infinite(glm::radians(50.0f), 2.0f, 0.25f)}, 200,
      100, cam);
  EXPECT_NEAR(r.near_m, 0.25, 1e-6);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(r.projection[i][j], v.projection[i][j], 1e-6) << i << "," << j;
}

void expect_rejected(const View& view, int w, int h, const std::string& path) {
  try {
    frame_view_of(view, w, h, Camera{});
    ADD_FAILURE() << "accepted a bad " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.info().path, path) << e.what();
  }
}

TEST(HostView, RejectsWhatIsNotARigidViewOrAPerspective) {
  const glm::mat4 p = glm::perspective(1.0f, 2.0f, 0.5f, 100.0f);
  expect_rejected(View{.view = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0)), .projection = p}, 200, 100,
                  "view.view");
  expect_rejected(View{.view = glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 1.0, 1.0)), .projection = p}, 200,
                  100, "view.view");
  expect_rejected(View{.projection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f)}, 200, 100, "view.projection");
  expect_rejected(View{.projection = p}, 100, 100, "view.projection");  // the aspect is not the targets'
  expect_rejected(View{.projection = glm::frustum(-1.0f, 3.0f, -1.0f, 1.0f, 0.5f, 100.0f)}, 200, 100,
                  "view.projection");
  // A forward projection read as reversed puts the near plane behind the camera.
  expect_rejected(View{.projection = p, .depth = DepthConvention::reversed}, 200, 100, "view.projection");
}

// --- With GL -------------------------------------------------------------------------------------

GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

constexpr int kW = 48, kH = 32;
// The first frame's ground against a later still frame's (frame 3, the same view 0.1 s on), pixel by
// pixel, relative. Measured on llvmpipe: 0 (the same values). The allowance is for the light moving in
// those 0.1 s (the clouds' shadows drift); drawn before render, the first frame's ground is 0.24% of
// the later one's (the air's light in front of it alone).
constexpr double kFirstFrameTolerance = 0.01;

std::unique_ptr<World> host_world() {
  gl().make_current();
  auto world = std::make_unique<World>();
  for (const auto* m : {&modules::atmosphere_module(), &modules::clouds_module(), &modules::godrays_module(),
                        &modules::terrain_module(), &modules::timeofday_module()})
    world->modules().add_static(*m);
  load_scene_file(*world, WELKIN_SOURCE_DIR "/examples/host-app/scene.json");
  return world;
}

struct HostTargets {
  GLuint color = 0, depth = 0, output = 0, framebuffer = 0;
  explicit HostTargets(GLenum color_format = GL_RGBA16F, int w = kW, int h = kH) {
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, color_format, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &output);
    glTextureStorage2D(output, 1, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, color, 0);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
  }
  ~HostTargets() {
    glDeleteFramebuffers(1, &framebuffer);
    const GLuint t[] = {color, depth, output};
    glDeleteTextures(3, t);
  }
  Targets targets() const {
    return {.color = color, .depth = depth, .output = output, .width = kW, .height = kH};
  }
  // The host's "geometry": the lower `rows` rows at `depth`, radiance `radiance`; the rest cleared.
  void fill(float radiance, float depth_value, float cleared_depth, int rows) const {
    const float c[4] = {radiance, radiance, radiance, 1.0f}, none[4] = {0, 0, 0, 1};
    glClearTexImage(color, 0, GL_RGBA, GL_FLOAT, none);
    glClearTexImage(depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &cleared_depth);
    glClearTexSubImage(color, 0, 0, 0, 0, kW, rows, 1, GL_RGBA, GL_FLOAT, c);
    glClearTexSubImage(depth, 0, 0, 0, 0, kW, rows, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth_value);
  }
  std::vector<uint8_t> read_output() const {
    std::vector<uint8_t> px(size_t(kW) * kH * 4);
    glGetTextureImage(output, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    return px;
  }
};

// East, away from the evening sun of the example's scene: a blue sky.
const glm::dmat4 kView = glm::lookAt(glm::dvec3(0, 0, 2), glm::dvec3(100, 20, 12), glm::dvec3(0, 0, 1));

Frame frame_of(const HostTargets& t, const glm::mat4& projection, DepthConvention c, uint64_t index) {
  return Frame{.view = {.view = kView, .projection = projection, .depth = c},
               .targets = t.targets(),
               .time_s = double(index) / 30.0,
               .dt_s = index ? 1.0 / 30.0 : 0.0,
               .index = index};
}

// A wall 2 km away over the lower third, drawn with forward and with reversed depth: the two frames
// agree, the sky lies above it, and the haze between it and the camera changed its radiance.
TEST(HostSky, ForwardAndReversedDepthComposeTheSameFrame) {
  const float fov = glm::radians(60.0f), aspect = float(kW) / kH, near = 0.5f;
  const glm::mat4 forward = glm::perspective(fov, aspect, near, 20000.0f),
                  reversed = reversed_infinite(fov, aspect, near);
  auto depth_at = [](const glm::mat4& p, bool fwd) {
    const glm::vec4 c = p * glm::vec4(0, 0, -2000.0f, 1.0f);
    return fwd ? 0.5f * c.z / c.w + 0.5f : c.z / c.w;
  };
  std::vector<uint8_t> out[2];
  float wall[2] = {0, 0};
  const float radiance = 2000.0f;
  for (int fwd = 0; fwd < 2; ++fwd) {
    auto world = host_world();
    Sky sky(*world);
    HostTargets t;
    for (uint64_t i = 0; i < 2; ++i) {
      t.fill(radiance, depth_at(fwd ? forward : reversed, fwd), fwd ? 1.0f : 0.0f, kH / 3);
      sky.render(frame_of(t, fwd ? forward : reversed,
                          fwd ? DepthConvention::forward : DepthConvention::reversed, i));
    }
    out[fwd] = t.read_output();
    float px[4];
    glGetTextureSubImage(t.color, 0, kW / 2, 2, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof px, px);
    wall[fwd] = px[1];
  }
  int worst = 0;
  for (size_t i = 0; i < out[0].size(); ++i)
    worst = std::max(worst, std::abs(int(out[0][i]) - int(out[1][i])));
  EXPECT_LE(worst, 2);
  // Air over 2 km: the wall's radiance is no longer what the host drew, but not far from it.
  EXPECT_NE(wall[1], radiance);
  EXPECT_GT(wall[1], 0.3f * radiance);
  EXPECT_LT(wall[1], 3.0f * radiance);
  EXPECT_NEAR(wall[0], wall[1], 0.01f * wall[1]);
  // The sky above the wall is the atmosphere's: blue over red, brighter than black, over the row
  // (the scene's clouds cover some of it, grey to beige).
  double red = 0.0, blue = 0.0;
  for (int x = 0; x < kW; ++x) {
    const uint8_t* top = &out[1][(size_t(kH - 2) * kW + size_t(x)) * 4];
    red += top[0] / double(kW), blue += top[2] / double(kW);
  }
  EXPECT_GT(blue, red);
  EXPECT_GT(blue, 40.0);
}

// The host's ground, 2 m below the camera, lit by Welkin's material functions (shade_lambert).
const char* kGroundVertex =
    "#version 450 core\nuniform mat4 u_view_projection;\nout vec3 v_p;\n"
    "void main() { v_p = vec3(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2e4 - 1e4, -2.0);\n"
    "  gl_Position = u_view_projection * vec4(v_p, 1.0); }\n";
const char* kGroundFragment =
    "in vec3 v_p;\nout vec4 o;\n"
    "void main() { o = vec4(shade_lambert(vec3(0.2), vec3(0, 0, 1), v_p), 1.0); }\n";

// A mistake in the host's fragment code is an error naming the host's code and carrying the compiler's
// log, its line counted from the host's code's first (Mesa names the source string of some errors
// as the first file's, so the test reads the line, not the file name the log gives).
TEST(HostSky, AMaterialProgramsErrorNamesTheHostsCode) {
  auto world = host_world();
  Sky sky(*world);
  EXPECT_NE(sky.material_program(kGroundVertex, kGroundFragment).id(), 0u);
  try {
    sky.material_program(kGroundVertex, "out vec4 o;\nvoid main() { o = shade_nothing(); }\n");
    ADD_FAILURE() << "compiled a call to a function that does not exist";
  } catch (const Error& e) {
    EXPECT_EQ(e.info().file, "the host's fragment code");
    EXPECT_NE(std::string(e.what()).find(":2:19: error: no function with name 'shade_nothing'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The composed HDR frame's green channel, row by row from the bottom.
std::vector<float> read_color(const HostTargets& t) {
  std::vector<float> px(size_t(kW) * kH * 4), green(size_t(kW) * kH);
  glGetTextureImage(t.color, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)), px.data());
  for (size_t i = 0; i < green.size(); ++i) green[i] = px[i * 4 + 1];
  return green;
}

// Drawn through render's draw_geometry, the host's materials read this frame's lights: the first
// frame's ground is lit as a later frame of the same still view is. Drawn before render, they read
// the last frame's lights, none before the first (the case draw_geometry is for).
TEST(HostSky, TheFirstFrameIsLitAsALaterStillFrame) {
  const glm::mat4 p = reversed_infinite(glm::radians(60.0f), float(kW) / kH, 0.5f);
  const glm::mat4 view_projection = p * glm::mat4(glm::dmat3(kView));  // rotation only: camera-relative
  // The rows wholly on the ground (the horizon lies above a third of the frame, looking 5.6 deg up).
  const size_t ground = size_t(kW) * (kH / 4);
  std::vector<float> frames[2][4];
  for (int in_frame = 0; in_frame < 2; ++in_frame) {
    auto world = host_world();
    Sky sky(*world);
    const Program ground_material = sky.material_program(kGroundVertex, kGroundFragment);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    HostTargets t;
    auto draw = [&] {
      glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer);
      glViewport(0, 0, kW, kH);
      glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // reversed depth
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_GREATER);
      glClearDepth(0.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      ground_material.use();
      ground_material.set("u_view_projection", view_projection);
      glBindVertexArray(vao);
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    };
    for (uint64_t i = 0; i < 4; ++i) {
      if (in_frame) {
        sky.render(frame_of(t, p, DepthConvention::reversed, i), draw);
      } else {
        sky.bind_material_lighting();
        draw();
        sky.render(frame_of(t, p, DepthConvention::reversed, i));
      }
      frames[in_frame][i] = read_color(t);
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    glDeleteVertexArrays(1, &vao);
  }
  // A later still frame is lit alike either way (the two paths agree once the lights exist).
  for (size_t i = 0; i < ground; ++i)
    ASSERT_NEAR(frames[0][3][i], frames[1][3][i], 1e-3f * frames[1][3][i]) << i;
  double first = 0.0, later = 0.0, before = 0.0, worst = 0.0;
  for (size_t i = 0; i < ground; ++i) {
    first += frames[1][0][i], later += frames[1][3][i], before += frames[0][0][i];
    worst = std::max(worst, std::abs(double(frames[1][0][i]) / frames[1][3][i] - 1.0));
  }
  EXPECT_LT(worst, kFirstFrameTolerance) << "first " << first << ", later " << later;
  // Drawn before render, the first frame's ground holds only the air's light in front of it.
  EXPECT_LT(before, 0.5 * later) << "before " << before << ", later " << later;
}

TEST(HostSky, BadTargetsAreOneClearError) {
  auto world = host_world();
  Sky sky(*world);
  const glm::mat4 p = reversed_infinite(1.0f, float(kW) / kH, 0.5f);
  auto path_of = [&](const Targets& t) -> std::string {
    try {
      sky.render(Frame{.view = {.view = kView, .projection = p}, .targets = t});
    } catch (const Error& e) {
      return e.info().path;
    }
    return "accepted";
  };
  HostTargets ldr(GL_RGBA8), good;
  EXPECT_EQ(path_of(ldr.targets()), "targets.color");  // 8-bit colour cannot hold radiance
  Targets swapped = good.targets();
  std::swap(swapped.color, swapped.depth);
  EXPECT_EQ(path_of(swapped), "targets.color");
  Targets no_depth = good.targets();
  no_depth.depth = 0;
  EXPECT_EQ(path_of(no_depth), "targets.depth");
  Targets bad_output = good.targets();
  bad_output.output = good.color;
  EXPECT_EQ(path_of(bad_output), "targets.output");
  Targets wrong_size = good.targets();
  wrong_size.width = kW + 1;
  EXPECT_EQ(path_of(wrong_size), "targets.color");
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

GLuint trivial_program() {
  const char* vs = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
  const char* fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
  GLuint p = glCreateProgram();
  for (auto [stage, src] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
    GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    glAttachShader(p, s);
    glDeleteShader(s);
  }
  glLinkProgram(p);
  return p;
}

GLint get_int(GLenum what) {
  GLint v = -1;
  glGetIntegerv(what, &v);
  return v;
}
GLint get_int(GLenum what, GLuint index) {
  GLint v = -1;
  glGetIntegeri_v(what, index, &v);
  return v;
}
GLint64 get_int64(GLenum what, GLuint index) {
  GLint64 v = -1;
  glGetInteger64i_v(what, index, &v);
  return v;
}
GLint bound_on_unit(GLuint unit, GLenum binding) {
  GLint active = get_int(GL_ACTIVE_TEXTURE);
  glActiveTexture(GL_TEXTURE0 + unit);
  GLint v = get_int(binding);
  glActiveTexture(GLenum(active));
  return v;
}

// Unusual state everywhere Welkin's passes touch, two frames (the first builds the tables), and every
// piece read back with glGet.
TEST(HostSky, LeavesTheHostsGlStateAsItFoundIt) {
  auto world = host_world();
  HostTargets t;
  GLuint read_fb = 0, vao = 0, tex[2] = {0, 0}, sampler = 0, buffers[3] = {0, 0, 0};
  glCreateFramebuffers(1, &read_fb);
  glCreateVertexArrays(1, &vao);
  glCreateTextures(GL_TEXTURE_2D, 2, tex);
  glTextureStorage2D(tex[0], 1, GL_RGBA8, 4, 4);
  glTextureStorage2D(tex[1], 1, GL_RGBA8, 4, 4);
  glCreateSamplers(1, &sampler);
  glCreateBuffers(3, buffers);
  for (GLuint b : buffers) glNamedBufferData(b, 1024, nullptr, GL_DYNAMIC_DRAW);
  const GLuint program = trivial_program();

  Sky sky(*world);  // construction is one of Welkin's calls too: set the state before the first frame
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.framebuffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fb);
  glUseProgram(program);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
  glBlendEquationSeparate(GL_FUNC_SUBTRACT, GL_MAX);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glClearDepth(0.25);
  glViewport(3, 5, 17, 11);
  glEnable(GL_SCISSOR_TEST);
  glScissor(1, 2, 3, 4);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glFrontFace(GL_CW);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glClearColor(0.125f, 0.25f, 0.375f, 0.5f);
  glEnable(GL_STENCIL_TEST);
  glEnable(GL_FRAMEBUFFER_SRGB);
  glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glBindTextureUnit(0, tex[0]);
  glBindTextureUnit(3, tex[1]);
  glBindTextureUnit(9, tex[0]);
  glBindSampler(1, sampler);
  glActiveTexture(GL_TEXTURE5);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 2);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers[1]);
  glBindBufferRange(GL_UNIFORM_BUFFER, 5, buffers[2], 256, 512);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[2]);
  glBindBuffer(GL_UNIFORM_BUFFER, buffers[0]);

  const glm::mat4 p = glm::perspective(glm::radians(60.0f), float(kW) / kH, 0.5f, 20000.0f);
  for (uint64_t i = 0; i < 2; ++i) {
    t.fill(1000.0f, 0.9f, 1.0f, kH / 4);
    sky.render(frame_of(t, p, DepthConvention::forward, i));
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

  EXPECT_EQ(get_int(GL_DRAW_FRAMEBUFFER_BINDING), GLint(t.framebuffer));
  EXPECT_EQ(get_int(GL_READ_FRAMEBUFFER_BINDING), GLint(read_fb));
  EXPECT_EQ(get_int(GL_CURRENT_PROGRAM), GLint(program));
  EXPECT_EQ(get_int(GL_VERTEX_ARRAY_BINDING), GLint(vao));
  EXPECT_EQ(get_int(GL_ARRAY_BUFFER_BINDING), GLint(buffers[0]));
  EXPECT_TRUE(glIsEnabled(GL_BLEND));
  EXPECT_EQ(get_int(GL_BLEND_SRC_RGB), GL_SRC_ALPHA);
  EXPECT_EQ(get_int(GL_BLEND_DST_RGB), GL_ONE_MINUS_SRC_ALPHA);
  EXPECT_EQ(get_int(GL_BLEND_SRC_ALPHA), GL_ONE);
  EXPECT_EQ(get_int(GL_BLEND_DST_ALPHA), GL_ZERO);
  EXPECT_EQ(get_int(GL_BLEND_EQUATION_RGB), GL_FUNC_SUBTRACT);
  EXPECT_EQ(get_int(GL_BLEND_EQUATION_ALPHA), GL_MAX);
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_EQ(get_int(GL_DEPTH_FUNC), GL_LEQUAL);
  GLboolean mask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
  EXPECT_EQ(mask, GL_FALSE);
  GLfloat clear_depth = 0.0f;
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &clear_depth);
  EXPECT_EQ(clear_depth, 0.25f);
  std::array<GLint, 4> viewport{}, scissor{};
  glGetIntegerv(GL_VIEWPORT, viewport.data());
  glGetIntegerv(GL_SCISSOR_BOX, scissor.data());
  EXPECT_EQ(viewport, (std::array<GLint, 4>{3, 5, 17, 11}));
  EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
  EXPECT_EQ(scissor, (std::array<GLint, 4>{1, 2, 3, 4}));
  EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
  EXPECT_EQ(get_int(GL_CULL_FACE_MODE), GL_FRONT);
  EXPECT_EQ(get_int(GL_FRONT_FACE), GL_CW);
  std::array<GLboolean, 4> color_mask{};
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask.data());
  EXPECT_EQ(color_mask, (std::array<GLboolean, 4>{GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE}));
  std::array<GLfloat, 4> clear_color{};
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_color.data());
  EXPECT_EQ(clear_color, (std::array<GLfloat, 4>{0.125f, 0.25f, 0.375f, 0.5f}));
  EXPECT_TRUE(glIsEnabled(GL_STENCIL_TEST));
  EXPECT_TRUE(glIsEnabled(GL_FRAMEBUFFER_SRGB));
  EXPECT_EQ(get_int(GL_CLIP_ORIGIN), GL_UPPER_LEFT);
  EXPECT_EQ(get_int(GL_CLIP_DEPTH_MODE), GL_NEGATIVE_ONE_TO_ONE);
  EXPECT_EQ(get_int(GL_ACTIVE_TEXTURE), GL_TEXTURE5);
  EXPECT_EQ(bound_on_unit(0, GL_TEXTURE_BINDING_2D), GLint(tex[0]));
  EXPECT_EQ(bound_on_unit(1, GL_TEXTURE_BINDING_2D), 0);
  EXPECT_EQ(bound_on_unit(3, GL_TEXTURE_BINDING_2D), GLint(tex[1]));
  EXPECT_EQ(bound_on_unit(9, GL_TEXTURE_BINDING_2D), GLint(tex[0]));
  EXPECT_EQ(bound_on_unit(2, GL_TEXTURE_BINDING_3D), 0);
  EXPECT_EQ(get_int(GL_SAMPLER_BINDING), 0);  // unit 5's
  EXPECT_EQ(bound_on_unit(1, GL_SAMPLER_BINDING), GLint(sampler));
  EXPECT_EQ(get_int(GL_UNPACK_ALIGNMENT), 1);
  EXPECT_EQ(get_int(GL_PACK_ALIGNMENT), 2);
  EXPECT_EQ(get_int(GL_UNIFORM_BUFFER_BINDING), GLint(buffers[0]));
  EXPECT_EQ(get_int(GL_UNIFORM_BUFFER_BINDING, 0), GLint(buffers[1]));
  EXPECT_EQ(get_int(GL_UNIFORM_BUFFER_BINDING, 5), GLint(buffers[2]));
  EXPECT_EQ(get_int64(GL_UNIFORM_BUFFER_START, 5), 256);
  EXPECT_EQ(get_int64(GL_UNIFORM_BUFFER_SIZE, 5), 512);
  EXPECT_EQ(get_int(GL_SHADER_STORAGE_BUFFER_BINDING, 2), GLint(buffers[2]));
  for (GLuint i : {1u, 2u, 3u, 4u, 6u, 7u}) EXPECT_EQ(get_int(GL_UNIFORM_BUFFER_BINDING, i), 0) << i;
  for (GLuint i = 0; i < 8; ++i) EXPECT_EQ(get_int(GL_IMAGE_BINDING_NAME, i), 0) << i;
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));

  // And Welkin did draw: sky over the host's ground.
  const std::vector<uint8_t> out = t.read_output();
  const uint8_t* top = &out[(size_t(kH - 2) * kW + kW / 2) * 4];
  EXPECT_GT(top[2], 40);

  glDeleteProgram(program);
  glDeleteFramebuffers(1, &read_fb);
  glDeleteVertexArrays(1, &vao);
  glDeleteTextures(2, tex);
  glDeleteSamplers(1, &sampler);
  glDeleteBuffers(3, buffers);
}

// A program deleted while current (GL keeps it until another is used) is gone once Welkin used its
// own: render's draw_geometry and its return find no program current, and no GL error.
TEST(HostSky, AProgramDeletedWhileCurrentComesBackAsNone) {
  auto world = host_world();
  Sky sky(*world);
  HostTargets t;
  const glm::mat4 p = reversed_infinite(1.0f, float(kW) / kH, 0.5f);
  glUseProgram(trivial_program());
  GLint current = get_int(GL_CURRENT_PROGRAM);
  glDeleteProgram(GLuint(current));
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  GLint inside = -1;
  sky.render(frame_of(t, p, DepthConvention::reversed, 0), [&] { inside = get_int(GL_CURRENT_PROGRAM); });
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_EQ(inside, 0);
  EXPECT_EQ(get_int(GL_CURRENT_PROGRAM), 0);
}

}  // namespace
