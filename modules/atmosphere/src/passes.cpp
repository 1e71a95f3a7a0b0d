// The atmosphere's frame: persistent LUTs imported into the render graph, regenerated only when the
// medium changes; per-frame sky-view LUT, sky irradiance and aerial-perspective froxels; then the
// sky behind everything and aerial perspective on the geometry in front of it.
#include <cmath>

#include "welkin/atmosphere/ground_region.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"

namespace welkin::atmosphere {

namespace {

// Shader permutations of one frame: software rasterisers run both sides of every branch, so
// features a frame does not use are compiled out rather than branched around.
bool moon_lights(const GpuUniforms& u) {
  return u.flags.w > 0.5f && glm::any(glm::greaterThan(glm::vec3(u.moon_illuminance), glm::vec3(0.0f)));
}

ShaderDefines moon_defines(const GpuUniforms& u) { return {{"ATM_MOON_LIGHT", moon_lights(u) ? "1" : "0"}}; }

bool in_space(const GpuUniforms& u) {
  return u.aerial_params.z > 0.5f;
}

// The persistent LUTs are a pure function of the medium, their sizes and step counts, the shaders
// that build them and the GL implementation that runs them: all of it is the disk cache's key.
std::string persistent_lut_key(const ShaderLibrary& shaders, const GpuUniforms& u) {
  std::string key = "welkin atmosphere: transmittance and multi-scattering LUTs, " +
                    std::to_string(kMultiscatteringLayers) + " layers\n";
  key += current_gl_info().key();
  key.append(reinterpret_cast<const char*>(&u), offsetof(GpuUniforms, camera_km));
  key.append(reinterpret_cast<const char*>(&u.transmittance_size), sizeof u.transmittance_size);
  key.append(reinterpret_cast<const char*>(&u.multiscattering_size), sizeof u.multiscattering_size);
  key += shaders.preprocess("atmosphere/transmittance_lut.comp", {}).text;
  for (const char* iterate : {"0", "1"})
    key += shaders.preprocess("atmosphere/multiscattering_lut.comp", {{"ATM_MS_ITERATE", iterate}}).text;
  return key;
}

size_t float_bytes(const Texture& t) {
  return size_t(t.desc().width) * size_t(t.desc().height) * 4 * sizeof(float);
}

// Both LUTs from the cache into their textures; false on a miss.
bool load_persistent_luts(const DiskCache& cache, const std::string& key, AtmosphereGpu& gpu) {
  const size_t t_bytes = float_bytes(*gpu.transmittance), ms_bytes = float_bytes(*gpu.multiscattering);
  const auto bytes = cache.read(key, t_bytes + ms_bytes);
  if (!bytes) return false;
  for (auto [texture, offset] : {std::pair{gpu.transmittance.get(), size_t(0)}, {gpu.multiscattering.get(), t_bytes}})
    glTextureSubImage2D(texture->id(), 0, 0, 0, texture->desc().width, texture->desc().height, GL_RGBA, GL_FLOAT,
                        bytes->data() + offset);
  return true;
}

void store_persistent_luts(const DiskCache& cache, const std::string& key, const AtmosphereGpu& gpu) {
  std::string bytes;
  for (const Texture* texture : {gpu.transmittance.get(), gpu.multiscattering.get()}) {
    const size_t n = float_bytes(*texture), at = bytes.size();
    bytes.resize(at + n);
    glGetTextureImage(texture->id(), 0, GL_RGBA, GL_FLOAT, GLsizei(n), bytes.data() + at);
  }
  cache.write(key, bytes);
}

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

void bind_for_materials(const AtmosphereGpu& gpu) {
  const AtmosphereGpu::Bindings& b = gpu.bindings;
  if (gpu.uniform_buffer) glBindBufferBase(GL_UNIFORM_BUFFER, b.block, gpu.uniform_buffer->id());
  auto bind = [](GLuint unit, const std::unique_ptr<Texture>& t) {
    if (t) glBindTextureUnit(unit, t->id());
  };
  bind(b.transmittance, gpu.transmittance);
  bind(b.multiscattering, gpu.multiscattering);
  bind(b.sky_view, gpu.sky_view);
  bind(b.aerial_inscattering, gpu.aerial_inscattering);
  bind(b.aerial_transmittance, gpu.aerial_transmittance);
  bind(b.sky_irradiance, gpu.sky_irradiance);
}

// What materials read of the atmosphere: the block as this frame uploads it and which builds of the
// LUTs (a LUT that this frame makes again is not valid until it runs; its build is counted then).
static uint64_t light_state(const AtmosphereGpu& gpu) {
  const int builds[4] = {gpu.lut_builds, gpu.lut_cache_reads, gpu.sky_view_builds, gpu.aerial_builds};
  const bool valid[3] = {gpu.luts_valid, gpu.sky_view_valid, gpu.aerial_valid};
  return fnv1a_64_of(gpu.uniforms, fnv1a_64_of(builds, fnv1a_64_of(valid)));
}

void add_light_term(World& world) {
  LightEnvironment& env = world.resource<LightEnvironment>();
  env.add(LightTerm{.name = "atmosphere",
                    .include = "atmosphere/light_term.glsl",
                    .lights = "atmosphere",
                    .priority = 10,
                    .aerial_perspective = "atmosphere_term_aerial_perspective",
                    .medium = "atmosphere_term_medium",
                    .textures = {"atmosphere.transmittance", "atmosphere.multiscattering", "atmosphere.sky_view",
                                 "atmosphere.aerial_inscattering", "atmosphere.aerial_transmittance",
                                 "atmosphere.sky_irradiance"},
                    .blocks = {"atmosphere"},
                    .bind = [&world](const LightEnvironment&) { bind_for_materials(world.resource<AtmosphereGpu>()); },
                    .state = [&world] { return light_state(world.resource<AtmosphereGpu>()); }});
  world.resource<AtmosphereGpu>().bindings = {.block = env.block("atmosphere"),
                                              .transmittance = env.unit("atmosphere.transmittance"),
                                              .multiscattering = env.unit("atmosphere.multiscattering"),
                                              .sky_view = env.unit("atmosphere.sky_view"),
                                              .aerial_inscattering = env.unit("atmosphere.aerial_inscattering"),
                                              .aerial_transmittance = env.unit("atmosphere.aerial_transmittance"),
                                              .sky_irradiance = env.unit("atmosphere.sky_irradiance")};
}

void lut_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  const Atmosphere atm = *reg.get<Atmosphere>(reg.first<Atmosphere>());
  const Entity sun_e = reg.first<Sun>(), moon_e = reg.first<Moon>(), stars_e = reg.first<Stars>();
  const Sun* sun = sun_e.is_null() ? nullptr : reg.get<Sun>(sun_e);
  const Moon* moon = moon_e.is_null() ? nullptr : reg.get<Moon>(moon_e);
  const Stars* stars = stars_e.is_null() ? nullptr : reg.get<Stars>(stars_e);
  // Values set in code or by other systems never passed the loaders' checks; a bad one is an error
  // naming the field, not a black image.
  auto check = [](const TypeDesc& type, const void* object) {
    try {
      check_object(type, object);
    } catch (const Error& e) {
      throw e.with_path_prefix(type.name);
    }
  };
  check(type_desc<Atmosphere>(), &atm);
  if (sun) check(type_desc<Sun>(), sun);
  if (moon) check(type_desc<Moon>(), moon);
  if (stars) check(type_desc<Stars>(), stars);

  auto& rc = sc.world.resource<RenderContext>();
  auto& gpu = sc.world.resource<AtmosphereGpu>();
  GpuUniforms u = make_uniforms(atm, sun, moon, rc.view);
  choose_aerial_frustum(u, gpu.aerial_uniforms, gpu.aerial_valid, gpu.uniforms.view_projection, gpu.view_turned);
  gpu.view_turned = u.view_projection != gpu.uniforms.view_projection;
  const ResolvedQuality q = resolve_quality(atm);

  // Persistent textures. Transmittance is float: long grazing paths keep relative precision.
  bool resized = ensure_texture(
      gpu.transmittance,
      {.width = q.transmittance_width, .height = q.transmittance_height, .format = TextureFormat::rgba32f});
  // Layers side by side, each with a one-texel gutter either side (multiscattering_lut.comp).
  const TextureDesc ms_desc{.width = kMultiscatteringLayers * (q.multiscattering_size + 2),
                            .height = q.multiscattering_size,
                            .format = TextureFormat::rgba32f};
  resized |= ensure_texture(gpu.multiscattering, ms_desc);
  if (q.multiscattering_iterations > 0) ensure_texture(gpu.multiscattering_scratch, ms_desc);
  if (ensure_texture(gpu.sky_view, {.width = q.sky_view_width, .height = q.sky_view_height, .format = rc.radiance_format()}))
    glTextureParameteri(gpu.sky_view->id(), GL_TEXTURE_WRAP_S, GL_REPEAT);  // azimuth is periodic
  const TextureDesc froxels{.width = q.aerial_perspective_width,
                            .height = q.aerial_perspective_height,
                            .depth = q.aerial_perspective_slices,
                            .format = rc.radiance_format()};
  ensure_texture(gpu.aerial_inscattering, froxels);
  ensure_texture(gpu.aerial_transmittance, froxels);
  ensure_texture(gpu.sky_irradiance,
                 {.width = 4, .height = 1, .format = TextureFormat::rgba32f, .linear_filter = false});
  if (!gpu.uniform_buffer) gpu.uniform_buffer = std::make_unique<Buffer>(sizeof(GpuUniforms));
  gpu.uniform_buffer->upload(&u, sizeof(u));
  gpu.uniforms = u;
  // The moon reaches surfaces where it lights the sky (make_uniforms): by day, on any surface, it adds
  // below a thousandth of what the sun and sky give (tested), and materials compile without it.
  LightEnvironment& env = sc.world.resource<LightEnvironment>();
  env.set_moon_lights_surfaces(moon_lights(u));
  env.install(rc.shaders);
  const bool rebuild = resized || !gpu.luts_valid || luts_differ(u, gpu.lut_uniforms);
  const bool space = in_space(u);
  const bool raymarch = atm.method == SkyMethod::raymarch;
  ShaderDefines moon_defs = moon_defines(u);
  // The sky view and the froxels hold radiance: half floats, or full ones for measurement.
  moon_defs["ATM_RADIANCE_FORMAT"] = rc.full_precision ? "rgba32f" : "rgba16f";
  ShaderDefines irradiance_defines = moon_defs;
  irradiance_defines["ATM_IRRADIANCE_MARCH"] = space || raymarch ? "1" : "0";

  RenderGraph& g = *sc.graph;
  const ResourceHandle trans = g.import("atmosphere.transmittance", *gpu.transmittance);
  const ResourceHandle ms = g.import("atmosphere.multiscattering", *gpu.multiscattering);
  const ResourceHandle sky_view = g.import("atmosphere.sky_view", *gpu.sky_view);
  const ResourceHandle ap_s = g.import("atmosphere.aerial_inscattering", *gpu.aerial_inscattering);
  const ResourceHandle ap_t = g.import("atmosphere.aerial_transmittance", *gpu.aerial_transmittance);
  const ResourceHandle irradiance = g.import("atmosphere.sky_irradiance", *gpu.sky_irradiance);
  for (auto [name, h] : {std::pair{"atmosphere.transmittance", trans},
                         {"atmosphere.multiscattering", ms},
                         {"atmosphere.sky_view", sky_view},
                         {"atmosphere.aerial_inscattering", ap_s},
                         {"atmosphere.aerial_transmittance", ap_t},
                         {"atmosphere.sky_irradiance", irradiance}})
    g.blackboard[name] = h;
  AtmosphereGpu* gp = &gpu;
  RenderContext* rcp = &rc;

  // A medium built before, by this program on this GL, is read back from the disk cache: on
  // llvmpipe the multi-scattering LUT is most of a start's GPU work.
  std::string lut_key;
  const DiskCache disk_cache = rebuild ? DiskCache::from_environment() : DiskCache();
  bool build_luts = rebuild;
  if (rebuild && disk_cache.enabled()) {
    lut_key = persistent_lut_key(rc.shaders, u);
    if (load_persistent_luts(disk_cache, lut_key, gpu)) {
      gpu.lut_uniforms = u;
      gpu.luts_valid = true;
      ++gpu.lut_cache_reads;
      build_luts = false;
    }
  }
  if (build_luts) {
    gpu.luts_valid = false;  // until the passes below have run
    // Persistent outputs nobody reads this frame must still be produced: side effects.
    g.add_pass(
        "atmosphere.transmittance",
        [&](PassBuilder& b) {
          b.write(trans);
          b.side_effect();
        },
        [gp, rcp, q](PassContext&) {
          bind_for_materials(*gp);
          bind_image_for_write(0, *gp->transmittance);
          dispatch_compute(rcp->shaders.compute("atmosphere/transmittance_lut.comp"),
                   group_count(q.transmittance_width, 8), group_count(q.transmittance_height, 8));
        });
    g.add_pass(
        "atmosphere.multiscattering",
        [&](PassBuilder& b) {
          b.read(trans);
          b.write(ms);
          b.side_effect();
        },
        [gp, rcp, q, u, lut_key, disk_cache](PassContext&) {
          bind_for_materials(*gp);
          // Hillaire's estimate, then passes that each read the last one's output and write the
          // other texture, ordered so that the final pass writes the LUT every reader binds.
          const int n = q.multiscattering_iterations;
          Texture* target[2] = {gp->multiscattering.get(), gp->multiscattering_scratch.get()};
          bind_image_for_write(0, *target[n % 2]);
          dispatch_compute(rcp->shaders.compute("atmosphere/multiscattering_lut.comp", {{"ATM_MS_ITERATE", "0"}}),
                   q.multiscattering_size, q.multiscattering_size);
          const Program& iterate =
              rcp->shaders.compute("atmosphere/multiscattering_lut.comp", {{"ATM_MS_ITERATE", "1"}});
          for (int k = n - 1; k >= 0; --k) {
            glBindTextureUnit(gp->bindings.multiscattering, target[(k + 1) % 2]->id());
            bind_image_for_write(0, *target[k % 2]);
            dispatch_compute(iterate, q.multiscattering_size, q.multiscattering_size);
          }
          glBindTextureUnit(gp->bindings.multiscattering, gp->multiscattering->id());
          gp->lut_uniforms = u;
          gp->luts_valid = true;
          ++gp->lut_builds;
          if (!lut_key.empty()) store_persistent_luts(disk_cache, lut_key, *gp);
        });
  }
  // The sky-view LUT serves the LUT method inside the atmosphere only; from space, and with method
  // raymarch, the sky is marched per pixel instead.
  // A LUT rebuilt below stays invalid if its pass is culled before it runs.
  const bool sky_view_stale = rebuild || !gpu.sky_view_valid || sky_view_differs(u, gpu.sky_view_uniforms);
  const bool aerial_stale = rebuild || !gpu.aerial_valid || aerial_perspective_differs(u, gpu.aerial_uniforms);
  if (sky_view_stale) gpu.sky_view_valid = false;
  if (aerial_stale) gpu.aerial_valid = false;
  if (!space && !raymarch && sky_view_stale) {
    g.add_pass(
        "atmosphere.sky_view",
        [&](PassBuilder& b) {
          b.read(trans);
          b.read(ms);
          b.write(sky_view);
        },
        [gp, rcp, q, moon_defs, u](PassContext&) {
          bind_for_materials(*gp);
          bind_image_for_write(0, *gp->sky_view);
          dispatch_compute(rcp->shaders.compute("atmosphere/sky_view_lut.comp", moon_defs),
                   group_count(q.sky_view_width, 8), group_count(q.sky_view_height, 8));
          gp->sky_view_uniforms = u;
          gp->sky_view_valid = true;
          ++gp->sky_view_builds;
        });
  }
  if (!space && aerial_stale) {
    g.add_pass(
        "atmosphere.aerial_perspective",
        [&](PassBuilder& b) {
          b.read(trans);
          b.read(ms);
          b.write(ap_s);
          b.write(ap_t);
          // Materials that write no depth (the clouds) read it through the light environment, which
          // the graph does not see: it is made whenever it is stale, geometry or not.
          b.side_effect();
        },
        [gp, rcp, q, moon_defs, u](PassContext&) {
          bind_for_materials(*gp);
          bind_image_for_write(0, *gp->aerial_inscattering);
          bind_image_for_write(1, *gp->aerial_transmittance);
          dispatch_compute(rcp->shaders.compute("atmosphere/aerial_perspective_volume.comp", moon_defs),
                   group_count(q.aerial_perspective_width, 8), group_count(q.aerial_perspective_height, 8));
          gp->aerial_uniforms = u;
          gp->aerial_valid = true;
          ++gp->aerial_builds;
        });
  }
  g.add_pass(
      "atmosphere.sky_irradiance",
      [&](PassBuilder& b) {
        b.read(trans);
        b.read(ms);
        b.read(sky_view);
        b.write(irradiance);
        b.side_effect();
      },
      [gp, rcp, irradiance_defines](PassContext&) {
        bind_for_materials(*gp);
        bind_image_for_write(0, *gp->sky_irradiance);
        dispatch_compute(rcp->shaders.compute("atmosphere/sky_irradiance.comp", irradiance_defines), 1, 1);
      });
}

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
            sc.graph->blackboard.at("atmosphere.transmittance"), in_space(gpu.uniforms)};
  }
  ResourceHandle published(const char* name) const { return graph->blackboard.at(name); }
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
  const ResourceHandle trans = f.trans, ms = f.published("atmosphere.multiscattering"),
                       sky_view = f.published("atmosphere.sky_view");
  const GpuUniforms& u = gpu.uniforms;
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
  const bool any_disc = u.flags.x > 0.5f || u.flags.z > 0.5f;
  // Stars only while the sun is below the camera's horizon, or from space: in daylight the sky
  // outshines them, and the pass would cost every frame for nothing.
  const glm::vec3 camera_up = glm::vec3(u.camera_km) / std::max(u.camera_km.w, 1e-6f);
  const bool draw_stars = stars && stars->count > 0 &&
                          (space || glm::dot(glm::vec3(u.sun_direction), camera_up) < 0.0f);
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
    GpuUniforms sky_u = u;  // the sky is at infinity: the aerial-perspective volume's frustum is not its input
    sky_u.aerial_view_projection = sky_u.aerial_inverse_view_projection = glm::mat4(0.0f);
    put(sky_u), put(gpu.sky_view_builds), put(gpu.lut_builds), put(gpu.lut_cache_reads), put(pixel_angle);
    put(rc.view.width), put(rc.view.height), put(rc.full_precision);
    for (const auto& [k, v] : discs) inputs += k + "=" + v + ";";
  }
  const TextureDesc color_desc{.width = rc.view.width, .height = rc.view.height, .format = rc.radiance_format()};
  if (!gpu.kept_sky || !(gpu.kept_sky->desc() == color_desc)) {
    gpu.kept_sky = std::make_unique<Texture>(color_desc);
    gpu.kept_sky_inputs.clear();
    gpu.drawn_sky_inputs.clear();
  }
  const ResourceHandle kept = g.import("atmosphere.kept_sky", *gpu.kept_sky);
  const bool keep = !inputs.empty() && inputs == gpu.kept_sky_inputs;
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
       draw_stars, stars_draw](PassContext& pc) {
        const Texture &color = pc.texture(t.color), &kept_sky = pc.texture(kept);
        if (keep) {
          copy_texture(kept_sky, color);
          return;
        }
        Framebuffer fb(&color, nullptr);
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        const bool ground_light = sky.at("ATM_SKY_GROUND_LIGHT") == "1";
        if (ground_light) env->bind();
        bind_for_materials(*gp);
        rcp->shaders.graphics("atmosphere/sky.vert", "atmosphere/sky.frag", ground_light ? open_sky : sky).use();
        rcp->draw_fullscreen_triangle();
        if (any_disc) {
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
  const GpuUniforms& u = f.gpu->uniforms;
  ShaderDefines ground_only = sky_defines(sc, f);
  if (ground_only.at("ATM_SKY_GROUND_LIGHT") != "1") return;
  const PixelRect ground = ground_pixel_rect(u, f.rc->view.width, f.rc->view.height);
  if (ground.empty()) return;
  ground_only["ATM_SKY_GROUND_ONLY"] = "1";
  const FrameTargets t = f.targets;
  const ResourceHandle trans = f.trans, ms = f.published("atmosphere.multiscattering"),
                       sky_view = f.published("atmosphere.sky_view");
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
      [gp = f.gpu, rcp = f.rc, env, t, ground, ground_only](PassContext& pc) {
        Framebuffer fb(&pc.texture(t.color), &pc.texture(t.depth));
        fb.bind();
        const DepthTestedOverlay open_pixels(GL_GEQUAL, ground);
        glDisable(GL_BLEND);
        env->bind();
        bind_for_materials(*gp);
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
  const ResourceHandle trans = f.trans, ap_s = f.published("atmosphere.aerial_inscattering"),
                       ap_t = f.published("atmosphere.aerial_transmittance");
  const GpuUniforms& u = gp->uniforms;
  const bool space = f.space;
  ShaderDefines ap = moon_defines(u);
  ap["ATM_AP_MODE"] = space ? "1" : "0";
  // Only where geometry may have written depth; without geometry there is nothing to apply it to.
  const PixelRect geometry = t.geometry;
  if (geometry.empty()) return;
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
      [gp, rcp, t, ap, geometry](PassContext& pc) {
        // Depth attached read-only and sampled with texelFetch at the fragment's own texel, which
        // GL 4.5 defines (9.3.1); GL_LESS against depth 0 passes only on geometry.
        Framebuffer fb(&pc.texture(t.color), &pc.texture(t.depth));
        fb.bind();
        const DepthTestedOverlay on_geometry(GL_LESS, geometry);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_SRC1_COLOR);  // colour * transmittance + in-scattering
        bind_for_materials(*gp);
        const Program& p =
            rcp->shaders.graphics("fullscreen.vert", "atmosphere/aerial_perspective_apply.frag", ap);
        glBindTextureUnit(0, pc.texture(t.depth).id());
        p.set("u_depth", 0);
        p.use();
        rcp->draw_fullscreen_triangle();
        glDisable(GL_BLEND);
      });
}

}  // namespace welkin::atmosphere
