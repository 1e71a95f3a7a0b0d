// The atmosphere's frame, drawn from its tables (passes.cpp): the sky behind everything, the ground's
// light where the geometry left the planet's ground open, and aerial perspective on the geometry in
// front of it. Each full-screen pass in its fragment or compute form (welkin/gfx/screen_pass.h).
#include <cmath>

#include "permutations.h"
#include "welkin/atmosphere/ground_region.h"
#include "welkin/atmosphere/gpu.h"
#include "graph_keys.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/screen_pass.h"

namespace welkin::atmosphere {

namespace {

// What the star pass needs of a frame, prepared outside the pass (the catalogue is rebuilt only when
// the field's parameters change).
struct StarsDraw {
  glm::mat3 celestial_to_world{1.0f};
  glm::vec2 viewport{1.0f};
  float focal_px = 1.0f;
  int count = 0;
};

bool same_catalogue(const Stars& a, const Stars& b) {
  return a.count == b.count && a.seed == b.seed && a.faintest_magnitude == b.faintest_magnitude &&
         a.brightness == b.brightness;
}

StarsDraw prepare_stars(AtmosphereGpu& gpu, const Stars& stars, const FrameView& view) {
  if (!gpu.stars || !same_catalogue(gpu.stars_built_from, stars)) {
    const std::vector<Star> catalogue = make_star_catalogue(stars);
    gpu.stars = std::make_unique<Buffer>(catalogue.size() * sizeof(Star), catalogue.data());
    gpu.stars_built_from = stars;
  }
  return {.celestial_to_world =
              glm::mat3(celestial_to_local(stars.local_sidereal_time_deg, stars.latitude_deg)),
          .viewport = glm::vec2(float(view.width), float(view.height)),
          .focal_px = float(view.height) / (2.0f * std::tan(0.5f * view.vertical_fov_rad)),
          .count = stars.count};
}

// Additive points over the sky (stars.vert), before the geometry that covers them.
void draw_star_points(RenderContext& rc, const AtmosphereGpu& gpu, const StarsDraw& s) {
  const Program& p = rc.shaders.graphics("atmosphere/stars.vert", "atmosphere/stars.frag");
  p.use();
  p.set("u_celestial_to_world", s.celestial_to_world);
  p.set("u_viewport", s.viewport);
  p.set("u_focal_px", s.focal_px);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gpu.stars->id());
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindVertexArray(rc.empty_vao.id());
  glDrawArrays(GL_POINTS, 0, s.count);
  glDisable(GL_BLEND);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

}  // namespace

// What the systems after lut_system read of the frame: the render context, the atmosphere's GPU
// state, the frame's targets and the tables lut_system published on the graph's blackboard.
struct AfterLuts {
  RenderContext* rc;
  AtmosphereGpu* gpu;
  RenderGraph* graph;
  FrameTargets targets;
  ResourceHandle trans;
  bool space;
  static AfterLuts of(SystemContext& sc) {
    AtmosphereGpu& gpu = sc.world.resource<AtmosphereGpu>();
    return {&sc.world.resource<RenderContext>(), &gpu, sc.graph, *sc.targets,
            sc.graph->published(kTransmittanceLut), in_space(gpu.uniforms)};
  }
  ResourceHandle published(GraphKey key) const { return graph->published(key); }
};

// The sky's shader: its mode (the sky-view LUT, the march from space, or method raymarch), and whether
// the planet's ground gets the light environment's shadows and added light (when some term has them).
ShaderDefines sky_defines(SystemContext& sc, const AfterLuts& f) {
  Registry& reg = sc.world.registry();
  const bool raymarch = reg.get<Atmosphere>(reg.first<Atmosphere>())->method == SkyMethod::raymarch;
  ShaderDefines sky = moon_defines(f.gpu->uniforms);
  sky["ATM_SKY_MODE"] = raymarch ? "2" : f.space ? "1" : "0";
  sky["ATM_SKY_GROUND_LIGHT"] = sc.world.resource<LightEnvironment>().shades_surfaces() ? "1" : "0";
  return sky;
}

// A full-screen triangle at depth 0 over the frame's depth, tested but not written, inside a
// rectangle of the frame (llvmpipe runs the depth test for every block a triangle touches, rejected or
// not; the scissor skips the rest): GL_LESS shades the geometry, GL_GEQUAL the pixels it left open.
// The frame's defaults come back at the end of the scope.
struct DepthTestedOverlay {
  DepthTestedOverlay(GLenum func, const PixelRect& inside) {
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDepthFunc(func);
    glEnable(GL_SCISSOR_TEST);
    glScissor(inside.x0, inside.y0, inside.x1 - inside.x0, inside.y1 - inside.y0);
  }
  ~DepthTestedOverlay() {
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
  }
  DepthTestedOverlay(const DepthTestedOverlay&) = delete;
  DepthTestedOverlay& operator=(const DepthTestedOverlay&) = delete;
};

// The sky over the whole target, before the geometry (which covers it: cheaper than testing depth per
// pixel afterwards; on a software rasteriser that test costs as much as a copy), and after the systems
// that make what the light environment reads (cloud shadows). The planet's ground shaded through the
// light environment is drawn after the geometry (ground_light_pass), where little of it is left.
void background_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  const Entity stars_e = reg.first<Stars>();
  const Stars* stars = stars_e.is_null() ? nullptr : reg.get<Stars>(stars_e);
  const AfterLuts f = AfterLuts::of(sc);
  AtmosphereGpu& gpu = *f.gpu;
  AtmosphereGpu* gp = f.gpu;
  RenderContext& rc = *f.rc;
  RenderContext* rcp = f.rc;
  RenderGraph& g = *sc.graph;
  const FrameTargets t = f.targets;
  const ResourceHandle trans = f.trans, ms = f.published(kMultiscatteringLut),
                       sky_view = f.published(kSkyViewLut);
  const FrameBlock& u = gpu.uniforms;
  const bool space = f.space;
  // The discs are hidden behind the geometry for free.
  const float pixel_angle = rc.view.vertical_fov_rad / float(std::max(rc.view.height, 1));
  const LightEnvironment* env = &sc.world.resource<LightEnvironment>();
  const ShaderDefines sky = sky_defines(sc, f);
  ShaderDefines discs = sky;
  discs["ATM_SKY_DISCS"] = "1";
  // With the ground's light: the sky without it everywhere here; the ground's shading comes after
  // the geometry (a branch would cost every pixel on a software rasteriser).
  ShaderDefines open_sky = sky;
  open_sky["ATM_SKY_GROUND_LIGHT"] = "0";
  const bool any_disc = u.sun_disc > 0.5f || u.moon_disc > 0.5f;
  // Stars only while the sun is below the camera's horizon, or from space: in daylight the sky
  // outshines them, and the pass would cost every frame for nothing.
  const glm::vec3 camera_up = u.camera_km / std::max(u.camera_radius_km, 1e-6f);
  const bool draw_stars = stars && stars->count > 0 && (space || glm::dot(u.sun_direction, camera_up) < 0.0f);
  StarsDraw stars_draw;
  if (draw_stars) stars_draw = prepare_stars(gpu, *stars, rc.view);
  // The sky's first draw covers every pixel without blending: the frame's colour needs no clear.
  sc.targets->color_covered = true;
  // What the sky and its discs are drawn from: the block (medium, view, sun, moon), the LUTs' builds,
  // the shaders' permutations, the frame's size and format. While they stay the same (a still view
  // under a still sun) the sky drawn last is copied in: exact, and a memory copy instead of a LUT
  // lookup per pixel. The stars turn with the clock: a frame with them draws.
  std::string inputs;
  if (!draw_stars) {
    auto put = [&inputs](const auto& v) { inputs.append(reinterpret_cast<const char*>(&v), sizeof v); };
    // the sky is at infinity: the aerial-perspective volume's frustum is not its input
    FrameBlock sky_u = u;
    sky_u.aerial_view_projection = sky_u.aerial_inverse_view_projection = glm::mat4(0.0f);
    put(sky_u), put(gpu.sky_view_builds), put(gpu.lut_builds), put(gpu.lut_cache_reads), put(pixel_angle);
    put(rc.view.width), put(rc.view.height), put(rc.full_precision);
    for (const auto& [k, v] : discs) inputs += k + "=" + v + ";";
  }
  const TextureDesc color_desc{
      .width = rc.view.width, .height = rc.view.height, .format = rc.radiance_format()};
  if (!gpu.kept_sky || !(gpu.kept_sky->desc() == color_desc)) {
    gpu.kept_sky = std::make_unique<Texture>(color_desc);
    gpu.kept_sky_inputs.clear();
    gpu.drawn_sky_inputs.clear();
  }
  const ResourceHandle kept = g.import("atmosphere.kept_sky", *gpu.kept_sky);
  const bool keep = !inputs.empty() && inputs == gpu.kept_sky_inputs;
  const bool compute = rc.forms.compute("atmosphere.sky");
  g.add_pass(
      "atmosphere.sky",
      [&](PassBuilder& b) {
        b.read(trans);
        b.read(ms);
        b.read(sky_view);
        b.read(t.color);
        b.write(t.color);
        b.read(kept);
        b.write(kept);
      },
      [gp, rcp, env, t, kept, keep, inputs = std::move(inputs), pixel_angle, sky, open_sky, discs, any_disc,
       draw_stars, stars_draw, compute](PassContext& pc) {
        const Texture &color = pc.texture(t.color), &kept_sky = pc.texture(kept);
        if (keep) {
          copy_texture(kept_sky, color);
          return;
        }
        const bool ground_light = sky.at("ATM_SKY_GROUND_LIGHT") == "1";
        if (ground_light) env->bind();
        bind_for_materials(*gp);
        Framebuffer fb(&color, nullptr);
        if (compute) {
          // One dispatch over the frame, the discs included (a dot product a pixel on a GPU).
          ShaderDefines with_discs = ground_light ? open_sky : sky;
          with_discs["ATM_SKY_DISCS"] = any_disc ? "1" : "0";
          with_discs["ATM_RADIANCE_FORMAT"] = image_format_qualifier(color.desc().format);
          const Program& p = rcp->shaders.compute("atmosphere/sky.comp", with_discs);
          p.set("u_pixel_angle", pixel_angle);
          bind_image_for_write(0, color);
          dispatch_screen(p, PixelRect{0, 0, color.desc().width, color.desc().height});
        }
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        if (!compute) {
          rcp->shaders.graphics("atmosphere/sky.vert", "atmosphere/sky.frag", ground_light ? open_sky : sky)
              .use();
          rcp->draw_fullscreen_triangle();
        }
        if (any_disc && !compute) {
          // Overwrites its squares with sky + disc (no blending: the sum must be fitted to RGBA16F).
          const Program& d = rcp->shaders.graphics("atmosphere/sky.vert", "atmosphere/sky.frag", discs);
          d.use();
          d.set("u_pixel_angle", pixel_angle);
          glBindVertexArray(rcp->empty_vao.id());
          glDrawArraysInstanced(GL_TRIANGLES, 0, 6, 2);
        }
        ++gp->sky_draws;
        // Recorded only once drawn (a failed frame draws again); kept when drawn twice alike.
        if (!inputs.empty() && inputs == gp->drawn_sky_inputs) {
          copy_texture(color, kept_sky);
          gp->kept_sky_inputs = inputs;
        }
        gp->drawn_sky_inputs = inputs;
        if (draw_stars) draw_star_points(*rcp, *gp, stars_draw);
      });
}

// The planet's ground lit through the light environment (its shadows and added light), after the
// geometry: over the part of the frame where rays can meet the ground, on the pixels the geometry left
// open (the depth test, early) whose rays meet the ground (the rest keeps the sky, discs and stars).
// Drawn before the geometry, every ground pixel paid the shading (11 copies in the default demo)
// and the terrain then covered most of them.
void ground_light_pass(SystemContext& sc, const AfterLuts& f) {
  const LightEnvironment* env = &sc.world.resource<LightEnvironment>();
  const FrameBlock& u = f.gpu->uniforms;
  ShaderDefines ground_only = sky_defines(sc, f);
  if (ground_only.at("ATM_SKY_GROUND_LIGHT") != "1") return;
  const PixelRect ground = ground_pixel_rect(u, f.rc->view.width, f.rc->view.height);
  if (ground.empty()) return;
  ground_only["ATM_SKY_GROUND_ONLY"] = "1";
  const bool compute = f.rc->forms.compute("atmosphere.ground_light");
  const FrameTargets t = f.targets;
  const ResourceHandle trans = f.trans, ms = f.published(kMultiscatteringLut),
                       sky_view = f.published(kSkyViewLut);
  sc.graph->add_pass(
      "atmosphere.ground_light",
      [&](PassBuilder& b) {
        b.read(trans);
        b.read(ms);
        b.read(sky_view);
        b.read(t.depth);
        b.read(t.color);
        b.write(t.color);
      },
      [gp = f.gpu, rcp = f.rc, env, t, ground, ground_only, compute](PassContext& pc) {
        env->bind();
        bind_for_materials(*gp);
        const Texture &color = pc.texture(t.color), &depth = pc.texture(t.depth);
        if (compute) {
          ShaderDefines d = ground_only;
          d["ATM_RADIANCE_FORMAT"] = image_format_qualifier(color.desc().format);
          const Program& p = rcp->shaders.compute("atmosphere/sky.comp", d);
          glBindTextureUnit(0, depth.id());
          bind_image_for_write(0, color);
          dispatch_screen(p, clipped(ground, color.desc().width, color.desc().height));
          return;
        }
        Framebuffer fb(&color, &depth);
        fb.bind();
        const DepthTestedOverlay open_pixels(GL_GEQUAL, ground);
        glDisable(GL_BLEND);
        rcp->shaders.graphics("atmosphere/sky.vert", "atmosphere/sky.frag", ground_only).use();
        rcp->draw_fullscreen_triangle();
      });
}

void sky_system(SystemContext& sc) {
  const AfterLuts f = AfterLuts::of(sc);
  ground_light_pass(sc, f);
  AtmosphereGpu* gp = f.gpu;
  RenderContext* rcp = f.rc;
  const FrameTargets t = f.targets;
  const ResourceHandle trans = f.trans, ap_s = f.published(kAerialInscattering),
                       ap_t = f.published(kAerialTransmittance);
  const FrameBlock& u = gp->uniforms;
  const bool space = f.space;
  ShaderDefines ap = moon_defines(u);
  ap["ATM_AP_MODE"] = space ? "1" : "0";
  // Only where geometry may have written depth; without geometry there is nothing to apply it to.
  const PixelRect geometry = t.geometry;
  if (geometry.empty()) return;
  const bool compute = rcp->forms.compute("atmosphere.aerial_perspective_apply");
  sc.graph->add_pass(
      "atmosphere.aerial_perspective_apply",
      [&](PassBuilder& b) {
        b.read(ap_s);
        b.read(ap_t);
        b.read(trans);
        b.read(t.depth);
        b.read(t.color);
        b.write(t.color);
      },
      [gp, rcp, t, ap, geometry, compute](PassContext& pc) {
        bind_for_materials(*gp);
        const Texture &color = pc.texture(t.color), &depth = pc.texture(t.depth);
        glBindTextureUnit(0, depth.id());
        if (compute) {
          ShaderDefines d = ap;
          d["ATM_RADIANCE_FORMAT"] = image_format_qualifier(color.desc().format);
          const Program& p = rcp->shaders.compute("atmosphere/aerial_perspective_apply.comp", d);
          bind_image_read_write(0, color);
          dispatch_screen(p, clipped(geometry, color.desc().width, color.desc().height));
          return;
        }
        // Depth attached read-only and sampled with texelFetch at the fragment's own texel, which
        // GL 4.5 defines (9.3.1); GL_LESS against depth 0 passes only on geometry.
        Framebuffer fb(&color, &depth);
        fb.bind();
        const DepthTestedOverlay on_geometry(GL_LESS, geometry);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_SRC1_COLOR);  // colour * transmittance + in-scattering
        const Program& p =
            rcp->shaders.graphics("fullscreen.vert", "atmosphere/aerial_perspective_apply.frag", ap);
        p.set("u_depth", 0);
        p.use();
        rcp->draw_fullscreen_triangle();
        glDisable(GL_BLEND);
      });
}

}  // namespace welkin::atmosphere
