#include "welkin/host/sky.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/host/gl_state.h"
#include "welkin/scene/field_path.h"

namespace welkin::host {

namespace {

// The host's targets for the frame being rendered (a world resource the geometry system reads).
struct HostInput {
  static constexpr std::string_view kTypeName = "host.Input";
  bool active = false;
  GLuint color = 0, depth = 0, sampler = 0;
  bool forward = false;
  glm::vec2 depth_terms{0.0f};
  uint64_t serial = 0;  // changes every frame: the host's geometry is never known unchanged
  // The host's drawing of its geometry (render's draw_geometry; null when drawn before), and its GL
  // state as render found it, put back around the call.
  const std::function<void()>* draw = nullptr;
  const GlStateGuard* host_state = nullptr;
};

// The host draws its geometry into its own targets with this frame's lights bound and its own GL
// state; Welkin's state is put back after.
void draw_host_geometry(const HostInput& input, World& world) {
  GlStateGuard welkin_state;
  input.host_state->restore();
  world.resource<LightEnvironment>().bind();
  (*input.draw)();
}

// The host's geometry is the frame's geometry, drawn where the engine's own is (order 0: after the
// sky behind it, before the aerial perspective and the clouds over it), depth-tested against
// whatever geometry the scene itself draws.
void host_geometry_system(SystemContext& sc) {
  const HostInput input = sc.world.resource<HostInput>();
  if (!input.active) return;
  auto& rc = sc.world.resource<RenderContext>();
  sc.targets->add_geometry(PixelRect{0, 0, rc.view.width, rc.view.height}, input.serial);
  const FrameTargets t = *sc.targets;
  sc.graph->add_pass(
      "host.geometry",
      [&](PassBuilder& b) {
        b.read(t.color);
        b.write(t.color);
        b.read(t.depth);
        b.write(t.depth);
      },
      [&rc, &world = sc.world, input, t](PassContext& pc) {
        if (input.draw) draw_host_geometry(input, world);
        Framebuffer fb(&pc.texture(t.color), &pc.texture(t.depth));
        fb.bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        const Program& p = rc.shaders.graphics("fullscreen.vert", "host/geometry.frag");
        p.use();
        p.set("u_forward", input.forward ? 1 : 0);
        p.set("u_depth_terms", input.depth_terms);
        p.set("u_near", rc.view.near_m);
        glBindTextureUnit(0, input.color);
        glBindTextureUnit(1, input.depth);
        glBindSampler(1, input.sampler);  // a depth texture sampled as values, whatever its compare mode
        rc.draw_fullscreen_triangle();
        glBindSampler(1, 0);
      });
}

Error target_error(const std::string& path, const std::string& expected, const std::string& found) {
  return Error(ErrorInfo{.path = path, .expected = expected, .found = found});
}

bool is_color_format(GLint f) {
  return f == GL_RGBA16F || f == GL_RGBA32F;
}
bool is_output_format(GLint f) {
  return f == GL_RGBA8 || f == GL_SRGB8_ALPHA8;
}
bool is_depth_format(GLint f) {
  return f == GL_DEPTH_COMPONENT16 || f == GL_DEPTH_COMPONENT24 || f == GL_DEPTH_COMPONENT32 ||
         f == GL_DEPTH_COMPONENT32F || f == GL_DEPTH24_STENCIL8 || f == GL_DEPTH32F_STENCIL8;
}

void check_target(GLuint name, const std::string& path, int width, int height, bool (*format_ok)(GLint),
                  const char* formats) {
  if (name == 0 || !glIsTexture(name)) throw target_error(path, "a texture name", std::to_string(name));
  GLint target = 0, w = 0, h = 0, format = 0;
  glGetTextureParameteriv(name, GL_TEXTURE_TARGET, &target);
  if (target != GL_TEXTURE_2D)
    throw target_error(path, "a GL_TEXTURE_2D texture", "target 0x" + std::to_string(target));
  glGetTextureLevelParameteriv(name, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(name, 0, GL_TEXTURE_HEIGHT, &h);
  glGetTextureLevelParameteriv(name, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  if (w != width || h != height)
    throw target_error(path, "the targets' size " + std::to_string(width) + "x" + std::to_string(height),
                       std::to_string(w) + "x" + std::to_string(h));
  if (!format_ok(format)) throw target_error(path, formats, "internal format " + std::to_string(format));
}

void check_targets(const Targets& t) {
  if (t.width < 1 || t.height < 1 || t.width > 16384 || t.height > 16384)
    throw target_error("targets", "a size between 1x1 and 16384x16384",
                       std::to_string(t.width) + "x" + std::to_string(t.height));
  check_target(t.color, "targets.color", t.width, t.height, is_color_format, "GL_RGBA16F or GL_RGBA32F");
  check_target(t.depth, "targets.depth", t.width, t.height, is_depth_format,
               "a depth or depth-stencil format");
  if (t.output)
    check_target(t.output, "targets.output", t.width, t.height, is_output_format,
                 "GL_RGBA8 or GL_SRGB8_ALPHA8");
}

// GL's defaults for what Welkin's passes take for granted and a host may have changed.
void welkin_defaults() {
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // Welkin's reversed Z
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_BLEND);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ZERO);
  glActiveTexture(GL_TEXTURE0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

}  // namespace

glm::vec2 depth_terms(const glm::mat4& p) {
  return {p[2][2], p[3][2]};
}

FrameView frame_view_of(const View& v, int width, int height, const Camera& camera) {
  const glm::dmat4& m = v.view;
  const glm::dmat3 r(m);
  const glm::dmat3 rtr = glm::transpose(r) * r;
  double off = std::abs(m[0][3]) + std::abs(m[1][3]) + std::abs(m[2][3]) + std::abs(m[3][3] - 1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) off += std::abs(rtr[i][j] - (i == j ? 1.0 : 0.0));
  if (!(off < 1e-4) || !(glm::determinant(r) > 0.0))
    throw Error(ErrorInfo{.path = "view.view",
                          .expected = "a rigid view matrix (a rotation and a translation)",
                          .found = "a matrix with scale, shear or a mirror"});
  const glm::dmat3 to_world = glm::transpose(r);
  const glm::dvec3 position = -(to_world * glm::dvec3(m[3]));
  const glm::mat4& p = v.projection;
  const double aspect = double(width) / double(height);
  const bool perspective = p[2][3] == -1.0f && p[3][3] == 0.0f && p[0][3] == 0.0f && p[1][3] == 0.0f &&
                           p[0][1] == 0.0f && p[1][0] == 0.0f && std::abs(p[2][0]) < 1e-6f &&
                           std::abs(p[2][1]) < 1e-6f && p[0][0] > 0.0f && p[1][1] > 0.0f &&
                           std::abs(double(p[1][1]) / double(p[0][0]) / aspect - 1.0) < 1e-3;
  if (!perspective)
    throw Error(ErrorInfo{.path = "view.projection",
                          .expected = "a symmetric perspective projection (w = -z) of the targets' aspect " +
                                      std::to_string(aspect),
                          .found = "another matrix"});
  // Depth toward infinity tends to ndc -a: beyond 1 (forward: -a >= 1) or at most 0 (reversed: -a <= 0).
  const glm::vec2 terms = depth_terms(p);
  const bool forward = v.depth == DepthConvention::forward;
  const float near_m = terms.y / ((forward ? -1.0f : 1.0f) + terms.x);
  if (!(forward ? terms.x <= -1.0f : terms.x >= 0.0f) || !(near_m > 0.0f && std::isfinite(near_m)))
    throw Error(
        ErrorInfo{.path = "view.projection",
                  .expected = std::string("a projection of ") + (forward ? "forward" : "reversed") +
                              " depth with its near plane in front of the camera",
                  .found = "depth terms " + std::to_string(terms.x) + ", " + std::to_string(terms.y)});
  FrameView fv =
      make_frame_view(position, glm::vec3(to_world[0]), glm::vec3(to_world[1]), -glm::vec3(to_world[2]),
                      2.0f * std::atan(1.0f / p[1][1]), near_m, width, height);
  fv.exposure =
      camera.exposure_mode == ExposureMode::ev100 ? exposure_from_ev100(camera.ev100) : camera.exposure;
  fv.tonemapper = camera.tonemapper;
  return fv;
}

Sky::Sky(World& world) : world_(world) {
  GlStateGuard guard;
  renderer_ = std::make_unique<Renderer>(world);
  glCreateFramebuffers(2, copy_framebuffers_);
  glCreateSamplers(1, &sampler_);
  glSamplerParameteri(sampler_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  world.scheduler().add(
      SystemDesc{.name = "host.geometry", .stage = Stage::geometry, .run = host_geometry_system});
}

Sky::~Sky() {
  glDeleteFramebuffers(2, copy_framebuffers_);
  glDeleteSamplers(1, &sampler_);
}

void Sky::copy(const Texture& from, GLuint to, int width, int height) {
  glNamedFramebufferTexture(copy_framebuffers_[0], GL_COLOR_ATTACHMENT0, from.id(), 0);
  glNamedFramebufferTexture(copy_framebuffers_[1], GL_COLOR_ATTACHMENT0, to, 0);
  glBlitNamedFramebuffer(copy_framebuffers_[0], copy_framebuffers_[1], 0, 0, width, height, 0, 0, width,
                         height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glNamedFramebufferTexture(copy_framebuffers_[0], GL_COLOR_ATTACHMENT0, 0, 0);
  glNamedFramebufferTexture(copy_framebuffers_[1], GL_COLOR_ATTACHMENT0, 0, 0);
}

FrameResult Sky::render(const Frame& frame, const std::function<void()>& draw_geometry) {
  const Targets& t = frame.targets;
  check_targets(t);
  Camera camera;
  const Registry& reg = world_.registry();
  if (const ComponentPool* pool = reg.pool(type_id<Camera>()); pool && !pool->empty())
    camera = *reg.get<Camera>(pool->entities()[0]);
  const FrameView view = frame_view_of(frame.view, t.width, t.height, camera);

  GlStateGuard guard;
  welkin_defaults();
  HostInput& input = world_.resource<HostInput>();
  input = HostInput{.active = true,
                    .color = t.color,
                    .depth = t.depth,
                    .sampler = sampler_,
                    .forward = frame.view.depth == DepthConvention::forward,
                    .depth_terms = depth_terms(frame.view.projection),
                    .serial = ++serial_,
                    .draw = draw_geometry ? &draw_geometry : nullptr,
                    .host_state = &guard};
  struct Deactivate {
    HostInput& input;
    ~Deactivate() { input.active = false; }
  } deactivate{input};
  FrameResult result = renderer_->render_view(
      FrameInfo{.time_s = frame.time_s, .dt_s = frame.dt_s, .index = frame.index}, view);
  copy(renderer_->hdr_texture(), t.color, t.width, t.height);
  if (t.output) copy(renderer_->output_texture(), t.output, t.width, t.height);
  check_gl("host frame");
  return result;
}

void Sky::set(std::string_view component, std::string_view path, const nlohmann::json& value) {
  set_scene_field(world_, component, path, value);
}

nlohmann::json Sky::get(std::string_view component, std::string_view path) {
  return get_scene_field(world_, component, path);
}

std::string Sky::material_glsl() {
  renderer_->prepare_shaders();
  return renderer_->context().shaders.preprocess("welkin/shading.glsl", {}).text;
}

Program Sky::material_program(std::string_view vertex, std::string_view fragment) {
  renderer_->prepare_shaders();
  ShaderSource fs = renderer_->context().shaders.preprocess("welkin/shading.glsl", {});
  fs.text += "#line 1 " + std::to_string(fs.files.size()) + "\n";
  fs.text += fragment;
  fs.files.push_back("the host's fragment code");
  const ShaderSource vs{.text = std::string(vertex), .files = {"the host's vertex shader"}};
  return link_program({{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}});
}

uint64_t Sky::lighting_version() const {
  return world_.resource<LightEnvironment>().version();
}

void Sky::bind_material_lighting() {
  world_.resource<LightEnvironment>().bind();
}

}  // namespace welkin::host
