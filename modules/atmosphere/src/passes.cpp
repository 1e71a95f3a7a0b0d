// The atmosphere's tables: persistent LUTs imported into the render graph, regenerated only when the
// medium changes; per-frame sky-view LUT, sky irradiance and aerial-perspective froxels. The passes
// that draw the frame from them are in frame_passes.cpp.
#include <cmath>

#include "welkin/atmosphere/gpu.h"
#include "graph_keys.h"
#include "permutations.h"
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

// The persistent LUTs are a pure function of the medium, their sizes and step counts, the shaders
// that build them and the GL implementation that runs them: all of it is the disk cache's key.
std::string persistent_lut_key(const ShaderLibrary& shaders, const FrameBlock& u) {
  std::string key = "welkin atmosphere: transmittance and multi-scattering LUTs, " +
                    std::to_string(kMultiscatteringLayers) + " layers\n";
  key += current_gl_info().key();
  const std::array<int, 6> sizes = persistent_lut_sizes(u);
  key.append(reinterpret_cast<const char*>(&u.medium), sizeof u.medium);
  key.append(reinterpret_cast<const char*>(sizes.data()), sizeof sizes);
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
  for (auto [texture, offset] :
       {std::pair{gpu.transmittance.get(), size_t(0)}, {gpu.multiscattering.get(), t_bytes}})
    glTextureSubImage2D(texture->id(), 0, 0, 0, texture->desc().width, texture->desc().height, GL_RGBA,
                        GL_FLOAT, bytes->data() + offset);
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
  env.add(LightTerm{
      .name = "atmosphere",
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
  world.resource<AtmosphereGpu>().bindings = {
      .block = env.block("atmosphere"),
      .transmittance = env.unit("atmosphere.transmittance"),
      .multiscattering = env.unit("atmosphere.multiscattering"),
      .sky_view = env.unit("atmosphere.sky_view"),
      .aerial_inscattering = env.unit("atmosphere.aerial_inscattering"),
      .aerial_transmittance = env.unit("atmosphere.aerial_transmittance"),
      .sky_irradiance = env.unit("atmosphere.sky_irradiance")};
}

namespace {

// Values set in code or by other systems never passed the loaders' checks; a bad one is an error
// naming the field, not a black image.
void check_inputs(const Atmosphere& atm, const Sun* sun, const Moon* moon, const Stars* stars) {
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
}

// The LUTs' textures at the quality's sizes; true when a persistent one was (re)allocated.
bool ensure_lut_textures(AtmosphereGpu& gpu, const ResolvedQuality& q, const RenderContext& rc) {
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
  if (ensure_texture(
          gpu.sky_view,
          {.width = q.sky_view_width, .height = q.sky_view_height, .format = rc.radiance_format()}))
    glTextureParameteri(gpu.sky_view->id(), GL_TEXTURE_WRAP_S, GL_REPEAT);  // azimuth is periodic
  const TextureDesc froxels{.width = q.aerial_perspective_width,
                            .height = q.aerial_perspective_height,
                            .depth = q.aerial_perspective_slices,
                            .format = rc.radiance_format()};
  ensure_texture(gpu.aerial_inscattering, froxels);
  ensure_texture(gpu.aerial_transmittance, froxels);
  ensure_texture(gpu.sky_irradiance,
                 {.width = 4, .height = 1, .format = TextureFormat::rgba32f, .linear_filter = false});
  return resized;
}

// What the atmosphere's passes of one frame share: its GPU state, the uniforms, the quality and the
// LUTs' handles in the graph.
struct LutFrame {
  AtmosphereGpu* gpu;
  RenderContext* rc;
  ResolvedQuality q;
  FrameBlock u;
  ShaderDefines moon_defs;
  ResourceHandle trans, ms, sky_view, ap_s, ap_t, irradiance;
};

// The transmittance and multi-scattering LUTs: built, or read back from the disk cache when this
// medium was built before by this program on this GL (on llvmpipe the multi-scattering LUT is most
// of a start's GPU work).
void add_persistent_lut_passes(RenderGraph& g, const LutFrame& f) {
  AtmosphereGpu& gpu = *f.gpu;
  std::string lut_key;
  const DiskCache disk_cache = DiskCache::from_environment();
  if (disk_cache.enabled()) {
    lut_key = persistent_lut_key(f.rc->shaders, f.u);
    if (load_persistent_luts(disk_cache, lut_key, gpu)) {
      gpu.lut_uniforms = f.u;
      gpu.luts_valid = true;
      ++gpu.lut_cache_reads;
      return;
    }
  }
  gpu.luts_valid = false;  // until the passes below have run
  AtmosphereGpu* gp = f.gpu;
  RenderContext* rcp = f.rc;
  const ResolvedQuality q = f.q;
  const FrameBlock u = f.u;
  // Persistent outputs nobody reads this frame must still be produced: side effects.
  g.add_pass(
      "atmosphere.transmittance",
      [&](PassBuilder& b) {
        b.write(f.trans);
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
        b.read(f.trans);
        b.write(f.ms);
        b.side_effect();
      },
      [gp, rcp, q, u, lut_key, disk_cache](PassContext&) {
        bind_for_materials(*gp);
        // Hillaire's estimate, then passes that each read the last one's output and write the
        // other texture, ordered so that the final pass writes the LUT every reader binds.
        const int n = q.multiscattering_iterations;
        Texture* target[2] = {gp->multiscattering.get(), gp->multiscattering_scratch.get()};
        bind_image_for_write(0, *target[n % 2]);
        dispatch_compute(
            rcp->shaders.compute("atmosphere/multiscattering_lut.comp", {{"ATM_MS_ITERATE", "0"}}),
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

void add_sky_view_pass(RenderGraph& g, const LutFrame& f) {
  AtmosphereGpu* gp = f.gpu;
  RenderContext* rcp = f.rc;
  g.add_pass(
      "atmosphere.sky_view",
      [&](PassBuilder& b) {
        b.read(f.trans);
        b.read(f.ms);
        b.write(f.sky_view);
      },
      [gp, rcp, q = f.q, moon_defs = f.moon_defs, u = f.u](PassContext&) {
        bind_for_materials(*gp);
        bind_image_for_write(0, *gp->sky_view);
        dispatch_compute(rcp->shaders.compute("atmosphere/sky_view_lut.comp", moon_defs),
                         group_count(q.sky_view_width, 8), group_count(q.sky_view_height, 8));
        gp->sky_view_uniforms = u;
        gp->sky_view_valid = true;
        ++gp->sky_view_builds;
      });
}

void add_aerial_perspective_pass(RenderGraph& g, const LutFrame& f) {
  AtmosphereGpu* gp = f.gpu;
  RenderContext* rcp = f.rc;
  g.add_pass(
      "atmosphere.aerial_perspective",
      [&](PassBuilder& b) {
        b.read(f.trans);
        b.read(f.ms);
        b.write(f.ap_s);
        b.write(f.ap_t);
        // Materials that write no depth (the clouds) read it through the light environment, which
        // the graph does not see: it is made whenever it is stale, geometry or not.
        b.side_effect();
      },
      [gp, rcp, q = f.q, moon_defs = f.moon_defs, u = f.u](PassContext&) {
        bind_for_materials(*gp);
        bind_image_for_write(0, *gp->aerial_inscattering);
        bind_image_for_write(1, *gp->aerial_transmittance);
        dispatch_compute(rcp->shaders.compute("atmosphere/aerial_perspective_volume.comp", moon_defs),
                         group_count(q.aerial_perspective_width, 8),
                         group_count(q.aerial_perspective_height, 8));
        gp->aerial_uniforms = u;
        gp->aerial_valid = true;
        ++gp->aerial_builds;
      });
}

void add_sky_irradiance_pass(RenderGraph& g, const LutFrame& f, const ShaderDefines& irradiance_defines) {
  AtmosphereGpu* gp = f.gpu;
  RenderContext* rcp = f.rc;
  g.add_pass(
      "atmosphere.sky_irradiance",
      [&](PassBuilder& b) {
        b.read(f.trans);
        b.read(f.ms);
        b.read(f.sky_view);
        b.write(f.irradiance);
        b.side_effect();
      },
      [gp, rcp, irradiance_defines](PassContext&) {
        bind_for_materials(*gp);
        bind_image_for_write(0, *gp->sky_irradiance);
        dispatch_compute(rcp->shaders.compute("atmosphere/sky_irradiance.comp", irradiance_defines), 1, 1);
      });
}

}  // namespace

void lut_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  const Atmosphere atm = *reg.get<Atmosphere>(reg.first<Atmosphere>());
  const Entity sun_e = reg.first<Sun>(), moon_e = reg.first<Moon>(), stars_e = reg.first<Stars>();
  const Sun* sun = sun_e.is_null() ? nullptr : reg.get<Sun>(sun_e);
  const Moon* moon = moon_e.is_null() ? nullptr : reg.get<Moon>(moon_e);
  const Stars* stars = stars_e.is_null() ? nullptr : reg.get<Stars>(stars_e);
  check_inputs(atm, sun, moon, stars);

  auto& rc = sc.world.resource<RenderContext>();
  auto& gpu = sc.world.resource<AtmosphereGpu>();
  FrameBlock u = make_uniforms(atm, sun, moon, rc.view);
  choose_aerial_frustum(u, gpu.aerial_uniforms, gpu.aerial_valid, gpu.uniforms.view_projection,
                        gpu.view_turned);
  gpu.view_turned = u.view_projection != gpu.uniforms.view_projection;
  const ResolvedQuality q = resolve_quality(atm);
  const bool resized = ensure_lut_textures(gpu, q, rc);
  if (!gpu.uniform_buffer) gpu.uniform_buffer = std::make_unique<Buffer>(sizeof(FrameBlock));
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
  LutFrame f{.gpu = &gpu, .rc = &rc, .q = q, .u = u, .moon_defs = moon_defs};
  auto publish = [&g](GraphKey key, Texture& texture) {
    const ResourceHandle h = g.import(std::string(key.name), texture);
    g.publish(key, h);
    return h;
  };
  f.trans = publish(kTransmittanceLut, *gpu.transmittance);
  f.ms = publish(kMultiscatteringLut, *gpu.multiscattering);
  f.sky_view = publish(kSkyViewLut, *gpu.sky_view);
  f.ap_s = publish(kAerialInscattering, *gpu.aerial_inscattering);
  f.ap_t = publish(kAerialTransmittance, *gpu.aerial_transmittance);
  f.irradiance = publish(kSkyIrradiance, *gpu.sky_irradiance);

  if (rebuild) add_persistent_lut_passes(g, f);
  // The sky-view LUT serves the LUT method inside the atmosphere only; from space, and with method
  // raymarch, the sky is marched per pixel instead.
  // A LUT rebuilt below stays invalid if its pass is culled before it runs.
  const bool sky_view_stale = rebuild || !gpu.sky_view_valid || sky_view_differs(u, gpu.sky_view_uniforms);
  const bool aerial_stale =
      rebuild || !gpu.aerial_valid || aerial_perspective_differs(u, gpu.aerial_uniforms);
  if (sky_view_stale) gpu.sky_view_valid = false;
  if (aerial_stale) gpu.aerial_valid = false;
  if (!space && !raymarch && sky_view_stale) add_sky_view_pass(g, f);
  if (!space && aerial_stale) add_aerial_perspective_pass(g, f);
  add_sky_irradiance_pass(g, f, irradiance_defines);
}

}  // namespace welkin::atmosphere
