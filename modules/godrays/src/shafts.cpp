// God rays: the atmosphere's aerial perspective adds the light that all the air in front of a surface
// scatters toward the camera; here the part that air in shadow does not scatter is found per ray, at a
// fraction of the frame's resolution, upsampled and subtracted from the frame. The haze is applied in
// the same pass.
#include "shafts.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "frame_block.h"
#include "welkin/core/world.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/screen_pass.h"
#include "welkin/scene/painted_map.h"

namespace welkin::godrays {

std::optional<glm::vec2> sun_on_screen(const glm::mat4& view_projection, const glm::vec3& sun_direction) {
  const glm::vec4 clip = view_projection * glm::vec4(sun_direction, 0.0f);
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  if (!(std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f)) return std::nullopt;
  return ndc * 0.5f + 0.5f;
}

MarchSteps march_steps(int steps) {
  steps = std::clamp(steps, 1, kMaxStepsPerRay);
  const int substeps = std::min(steps, kSubsteps);
  return {(steps + substeps - 1) / substeps, substeps};
}

namespace {

// The planet below the camera, as the shaders see it: up, radius and altitude (from doubles, so the
// ground distance keeps its precision a metre above the surface).
struct PlanetView {
  glm::vec3 up;
  glm::vec2 radius_altitude;
};
PlanetView planet_view(const MapFrame& planet, const glm::dvec3& camera_m) {
  const glm::dvec3 from_centre = camera_m - planet.planet_center_m;
  const double r = glm::length(from_centre);
  return {glm::vec3(from_centre / r),
          glm::vec2(float(planet.planet_radius_m), float(r - planet.planet_radius_m))};
}

// Whether the sun stands above the horizon of a point `reach_m` above the camera (the planet's
// dip below the level there). With the shafts' reach: whether any air a ray reaches can see the sun
// (the highest point is the camera's height plus that distance); with 0: the camera's own horizon.
bool sun_lights_air(const MapFrame& planet, const glm::vec3& sun, const glm::dvec3& camera_m, float reach_m) {
  const glm::dvec3 from_centre = camera_m - planet.planet_center_m;
  const double r = glm::length(from_centre) + double(reach_m);
  const double dip = std::acos(std::clamp(planet.planet_radius_m / r, -1.0, 1.0));
  const double elevation = std::asin(
      std::clamp(double(glm::dot(glm::dvec3(sun), from_centre / glm::length(from_centre))), -1.0, 1.0));
  return elevation > -dip;
}

// The shafts' loss at its resolution, in the pass's form (welkin/gfx/screen_pass.h); `frame`: the
// frame's block (frame_block.h).
void run_shafts(RenderContext& rc, World& world, const Texture& target, const Texture& depth,
                const ShaderDefines& defines, const Buffer& frame) {
  const bool compute = rc.forms.compute("godrays.shafts");
  world.resource<LightEnvironment>().bind();
  glBindTextureUnit(0, depth.id());
  ShaderDefines d = defines;
  if (compute) d["GODRAYS_LOSS_FORMAT"] = image_format_qualifier(target.desc().format);
  const Program& p = compute ? rc.shaders.compute("godrays/shafts.comp", d)
                             : rc.shaders.graphics("fullscreen.vert", "godrays/shafts.frag", d);
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlockBinding, frame.id());
  if (compute) {
    bind_image_for_write(0, target);
    dispatch_screen(p, PixelRect{0, 0, target.desc().width, target.desc().height});
    return;
  }
  Framebuffer fb(&target, nullptr);
  fb.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  p.use();
  rc.draw_fullscreen_triangle();
}

struct ApplyDraw {
  bool shafts = false, haze = false, tiles = false;
  glm::ivec2 loss_size{1};
  ShaderDefines defines;
};

// The shafts and the haze applied to the frame, in the pass's form: blending over a triangle (or the
// tiles the shafts touch), or a compute pass loading and storing the frame in place.
void run_apply(RenderContext& rc, World& world, const Texture& color, const Texture* loss,
               const Texture* depth, const ApplyDraw& a, const Buffer& frame) {
  const bool compute = rc.forms.compute("godrays.apply");
  if (loss) glBindTextureUnit(0, loss->id());
  if (depth) {
    world.resource<LightEnvironment>().bind();
    glBindTextureUnit(1, depth->id());
  }
  ShaderDefines d = a.defines;
  if (compute) d["GODRAYS_COLOR_FORMAT"] = image_format_qualifier(color.desc().format);
  const Program& p = compute ? rc.shaders.compute("godrays/apply.comp", d)
                             : rc.shaders.graphics("godrays/apply.vert", "godrays/apply.frag", d);
  if (a.haze) glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlockBinding, frame.id());
  if (compute) {
    bind_image_read_write(0, color);
    dispatch_screen(p, PixelRect{0, 0, color.desc().width, color.desc().height});
    return;
  }
  Framebuffer fb(&color, nullptr);
  fb.bind();
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  if (a.haze) {
    // haze light - shafts + the haze's transmittance x the frame; the frame's alpha stays
    glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
  } else {
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);  // the frame less the shafts (alpha less 0)
    glBlendFunc(GL_ONE, GL_ONE);
  }
  p.use();
  if (a.tiles) {
    const glm::ivec2 count = (a.loss_size + kApplyTileTexels - 1) / kApplyTileTexels;
    glBindVertexArray(rc.empty_vao.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count.x * count.y);
  } else {
    rc.draw_fullscreen_triangle();
  }
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);
}

}  // namespace

void shafts_system(SystemContext& sc) {
  World& world = sc.world;
  Registry& reg = world.registry();
  const GodRays* rays = reg.first<GodRays>().is_null() ? nullptr : reg.get<GodRays>(reg.first<GodRays>());
  const Haze* haze = reg.first<Haze>().is_null() ? nullptr : reg.get<Haze>(reg.first<Haze>());
  auto& rc = world.resource<RenderContext>();
  const FrameView view = rc.view;
  const std::optional<glm::vec3> sun = scene_sun_direction(world);
  const MapFrame planet = scene_map_frame(world, 1.0);
  const PlanetView ground = planet_view(planet, view.camera_position_m);
  // The shafts run where some air within their reach sees the sun.
  bool shafts = rays && sun && sun_lights_air(planet, *sun, view.camera_position_m, rays->max_distance_m);
  std::optional<glm::vec2> sun_uv;
  if (shafts && rays->method == ShaftMethod::screen_space) {
    // The screen-space estimate needs the sun's image, on the screen and above the camera's horizon.
    sun_uv = sun_on_screen(view.view_projection, *sun);
    shafts = sun_uv.has_value() && sun_lights_air(planet, *sun, view.camera_position_m, 0.0f);
  }
  if (!shafts && !haze) return;
  const char* with_haze = haze ? "1" : "0";
  // The block both passes read: the view ray, the planet, the haze, the sun (and the shafts' own).
  FrameBlock block{};
  block.inverse_view_projection = view.inverse_view_projection;
  block.up = ground.up;
  block.planet_radius_m = ground.radius_altitude.x;
  block.camera_altitude_m = ground.radius_altitude.y;
  if (haze) {
    block.haze_density_per_m = haze->density_per_m;
    block.haze_inverse_height_per_m = 1.0f / haze->scale_height_m;
    block.haze_scattering = haze->scattering;
    block.haze_absorption = haze->absorption;
    block.haze_g = haze->phase_g;
  }
  block.sun_direction = sun.value_or(glm::vec3(0.0f, 0.0f, 1.0f));
  if (shafts) {
    const glm::vec2 sun_at = sun_uv.value_or(glm::vec2(0.5f));
    block.max_distance_m = rays->max_distance_m;
    block.reach = rays->screen_reach;
    block.sun_u = sun_at.x, block.sun_v = sun_at.y;
    // The jitter moves with the frame, and a frame of a sequence draws the same noise when scrubbed.
    block.jitter = float(std::fmod(double(sc.frame.index) * 0.6180339887498949, 1.0));
  }
  std::unique_ptr<Buffer>& frame_buffer = world.resource<GodRaysGpu>().frame;
  if (!frame_buffer) frame_buffer = std::make_unique<Buffer>(sizeof(FrameBlock));
  frame_buffer->upload(&block, sizeof(block));
  const Buffer* frame = frame_buffer.get();

  const FrameTargets t = *sc.targets;
  RenderGraph& g = *sc.graph;
  ResourceHandle loss;
  glm::ivec2 loss_size(1);
  if (shafts) {
    const int d = std::max(rays->resolution_divisor, 1);
    const int w = std::max((view.width + d - 1) / d, 1), h = std::max((view.height + d - 1) / d, 1);
    loss_size = {w, h};
    const MarchSteps march = march_steps(rays->steps);
    // Counts are compiled in: llvmpipe runs a loop of run-time length for its whole group of pixels.
    const ShaderDefines defines = {
        {"GODRAYS_METHOD", rays->method == ShaftMethod::marched ? "0" : "1"},
        {"GODRAYS_SEGMENTS", std::to_string(march.segments)},
        {"GODRAYS_SUBSTEPS", std::to_string(march.substeps)},
        {"GODRAYS_SCREEN_SAMPLES", std::to_string(std::clamp(rays->screen_samples, 1, kMaxStepsPerRay))},
        {"GODRAYS_AIR_STEPS", std::to_string(std::clamp(rays->air_steps, 1, kMaxStepsPerRay))},
        {"GODRAYS_JITTER", rays->jitter ? "1" : "0"},
        {"GODRAYS_HAZE", with_haze}};
    loss = g.create("godrays.loss", TextureDesc{.width = w, .height = h, .format = rc.radiance_format()});
    g.add_pass(
        "godrays.shafts",
        [&](PassBuilder& b) {
          b.read(t.depth);
          b.write(loss);
        },
        [&rc, &world, t, loss, defines, frame](PassContext& pc) {
          run_shafts(rc, world, pc.texture(loss), pc.texture(t.depth), defines, *frame);
        });
    // The marched shafts' jitter is filtered out at their resolution; the screen-space path stays
    // unfiltered to stay cheap (its taps' jitter shows as fine noise).
    if (rays->jitter && rays->method == ShaftMethod::marched) {
      const ResourceHandle filtered = g.create(
          "godrays.loss_filtered", TextureDesc{.width = w, .height = h, .format = rc.radiance_format()});
      g.add_pass(
          "godrays.filter",
          [&](PassBuilder& b) {
            b.read(loss);
            b.write(filtered);
          },
          [&rc, loss, filtered](PassContext& pc) {
            Framebuffer fb(&pc.texture(filtered), nullptr);
            fb.bind();
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_BLEND);
            glBindTextureUnit(0, pc.texture(loss).id());
            rc.shaders.graphics("fullscreen.vert", "godrays/filter.frag").use();
            rc.draw_fullscreen_triangle();
          });
      loss = filtered;
    }
  }
  // The screen-space shafts alone are drawn tile by tile, skipping the tiles they leave unchanged
  // (apply.vert): they are zero wherever no tap toward the sun meets geometry. The marched shafts
  // are nowhere zero under broken cloud, and their tiles cost 1.56 ms against the triangle's 1.08.
  const bool tiles = shafts && !haze && rays->method == ShaftMethod::screen_space;
  const ShaderDefines apply_defines = {{"GODRAYS_SHAFTS", shafts ? "1" : "0"},
                                       {"GODRAYS_HAZE", with_haze},
                                       {"GODRAYS_TILES", tiles ? "1" : "0"},
                                       {"GODRAYS_TILE_TEXELS", std::to_string(kApplyTileTexels)}};
  g.add_pass(
      "godrays.apply",
      [&](PassBuilder& b) {
        if (shafts) b.read(loss);
        if (haze) b.read(t.depth);
        b.read(t.color);
        b.write(t.color);
      },
      [&rc, &world, t, loss, frame,
       draw = ApplyDraw{shafts, haze != nullptr, tiles, loss_size, apply_defines}](PassContext& pc) {
        run_apply(rc, world, pc.texture(t.color), draw.shafts ? &pc.texture(loss) : nullptr,
                  draw.haze ? &pc.texture(t.depth) : nullptr, draw, *frame);
      });
}

}  // namespace welkin::godrays
