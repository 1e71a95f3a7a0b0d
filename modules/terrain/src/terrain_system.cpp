// Render system of the terrain module: places each terrain, picks chunk levels of detail, culls
// chunks outside the view, draws the cascaded shadow maps, then the chunks' surface (depth and each
// pixel's material inputs) and its light (the runtime's PBR shading, once per pixel); a still view
// takes the terrain it drew last.
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "terrain_gpu.h"
#include "terrain_passes.h"
#include "terrain_system.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/shared_state.h"

namespace welkin::terrain {

namespace {

constexpr double kEarthRadiusM = 6371008.8;  // mean radius, for geodetic offsets

struct Cascades {
  std::array<glm::mat4, 3> light_view_projection;  // camera-relative world -> cascade clip space
  std::array<float, 3> far_m;                       // each cascade covers view distances up to this
  std::array<float, 3> extent_m;                    // side of each cascade's square, for texel-sized biases
  std::array<glm::dvec3, 3> centre_m;               // in the scene frame, on the cascade's grid
};

// Orthographic cascades around slices of the view frustum; each reaches `reach_m` toward the sun to
// catch mountains behind the view. A slice's bounding sphere keeps its size as the camera turns; its
// centre is put on a grid fixed in the scene (in the light's axes, steps of an eighth of the radius,
// the radius grown by one step so that the slice stays inside), so a cascade stays where it is, and
// its depths stay what they were, while the camera turns or moves: 12.5% coarser texels for cascades
// that are drawn again only when they move (or their casters or the sun do). A cascade stays where
// the last frame had it (`previous`) for as long as its slice stays inside it, up to a whole step
// from its centre in each of the light's axes: a turn or a flight moves it half as often as snapping
// every frame would.
Cascades make_cascades(const FrameView& v, const glm::vec3& sun, float distance_m, float reach_m,
                       const std::optional<TerrainCache::CascadePlaces>& previous) {
  Cascades c;
  const float splits[4] = {v.near_m, distance_m * 0.03f, distance_m * 0.2f, distance_m};
  const float ty = std::tan(v.vertical_fov_rad * 0.5f), tx = ty * float(v.width) / float(v.height);
  glm::vec3 up = std::abs(sun.z) > 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  // The light's axes (those of glm::lookAt toward -sun with `up`).
  const glm::dvec3 f = -glm::dvec3(sun), s = glm::normalize(glm::cross(f, glm::dvec3(up))),
                   u = glm::cross(s, f);
  for (int i = 0; i < 3; ++i) {
    // The slice in the view's own axes (right, up, forward), so that its radius is the same number
    // however the view is turned (computed from turned corners, it changed in its last bits, and the
    // cascade with it).
    glm::vec3 corners[8];
    for (int k = 0; k < 8; ++k) {
      float d = splits[i + (k >> 2)];
      corners[k] = glm::vec3((k & 1 ? tx : -tx) * d, (k & 2 ? ty : -ty) * d, d);
    }
    glm::vec3 local(0.0f);
    for (const auto& p : corners) local += p / 8.0f;
    float radius = 0.0f;
    for (const auto& p : corners) radius = std::max(radius, glm::length(p - local));
    const glm::vec3 centre = v.right * local.x + v.up * local.y + v.forward * local.z;
    const double step = radius / 8.0;
    const glm::dvec3 world = v.camera_position_m + glm::dvec3(centre);
    auto snap = [step](double x) { return std::round(x / step) * step; };
    glm::dvec3 snapped =
        s * snap(glm::dot(world, s)) + u * snap(glm::dot(world, u)) + f * snap(glm::dot(world, f));
    radius += float(step);
    if (previous && previous->extent_m[size_t(i)] == 2.0f * radius) {
      const glm::dvec3 d = world - previous->centre_m[size_t(i)];
      if (std::abs(glm::dot(d, s)) <= step && std::abs(glm::dot(d, u)) <= step &&
          std::abs(glm::dot(d, f)) <= step)
        snapped = previous->centre_m[size_t(i)];
    }
    const glm::vec3 rel = glm::vec3(snapped - v.camera_position_m);
    glm::mat4 view = glm::lookAt(rel + sun * (radius + reach_m), rel, up);
    glm::mat4 proj = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.0f, 2.0f * radius + reach_m);
    c.light_view_projection[size_t(i)] = proj * view;
    c.far_m[size_t(i)] = splits[i + 1];
    c.extent_m[size_t(i)] = 2.0f * radius;
    c.centre_m[size_t(i)] = snapped;
  }
  return c;
}

bool outside_view(const glm::mat4& view_projection, const glm::vec3& lo, const glm::vec3& hi) {
  int out[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 8; ++i) {
    glm::vec4 c =
        view_projection * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
    out[0] += c.x < -c.w;
    out[1] += c.x > c.w;
    out[2] += c.y < -c.w;
    out[3] += c.y > c.w;
    out[4] += c.w <= 0.0f;  // behind the camera (infinite far plane: nothing to test beyond)
  }
  for (int k = 0; k < 5; ++k)
    if (out[k] == 8) return true;
  return false;
}

// What one cascade's depths are drawn from, in the scene's frame (the camera's position aside: a
// cascade that stays put keeps its depths as the camera moves): where it is, the sun, the atlas's
// size, and each caster's mesh, placement and the levels drawn.
std::string cascade_inputs(const Cascades& c, int i, const glm::vec3& sun, const std::vector<Placed>& placed,
                           int size) {
  std::string bytes;
  auto put = [&bytes](const auto& v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(c.centre_m[size_t(i)]), put(c.extent_m[size_t(i)]), put(sun), put(size);
  for (const Placed& p : placed) {
    put(p.gpu), put(p.anchor_m), put(p.rotation), put(p.inverse_two_radius);
    for (const Draw& d : p.shadow_draws[size_t(i)]) put(d.first), put(d.count);
  }
  return bytes;
}

// What the view's terrain is drawn from: each terrain's mesh, placement and the levels drawn, the
// view, the frame's size and format, the shaders, and the light environment (its composition and
// every term's state: the sun, the sky, the cascades, the clouds' shadows). None when a term cannot
// say what it reads: then the terrain is drawn every frame.
std::optional<uint64_t> view_inputs(const std::vector<Placed>& placed, const RenderContext& rc,
                                    const LightEnvironment& env) {
  const std::optional<uint64_t> light = env.state();
  if (!light) return std::nullopt;
  const FrameView& v = rc.view;
  uint64_t h = fnv1a_64_of(*light, fnv1a_64_of(env.version(), fnv1a_64_of(env.moon_lights_surfaces())));
  h = fnv1a_64_of(v.view_projection, fnv1a_64_of(v.camera_position_m, h));
  const int frame[3] = {v.width, v.height, int(rc.full_precision)};
  h = fnv1a_64_of(frame, fnv1a_64_of(rc.shaders.environment_version(), h));
  for (const Placed& p : placed) {
    h = fnv1a_64_of(p.inverse_two_radius,
                    fnv1a_64_of(p.rotation, fnv1a_64_of(p.anchor_m, fnv1a_64_of(p.gpu, h))));
    h = fnv1a_64(
        std::string_view(reinterpret_cast<const char*>(p.draws.data()), p.draws.size() * sizeof(Draw)), h);
  }
  return h;
}

}  // namespace

glm::dvec3 anchor_position(World& world, const Terrain& t) {
  switch (t.anchor) {
    case Anchor::scene_origin: return {0.0, 0.0, t.height_m};
    case Anchor::offset: return t.offset_m + glm::dvec3(0.0, 0.0, t.height_m);
    case Anchor::geodetic: {
      const PlanetFrame* planet = world.find_resource<PlanetFrame>();
      if (!planet || !planet->origin)
        throw Error(ErrorInfo{.path = "terrain.Terrain/anchor",
                              .expected = "a scene whose origin has a latitude and longitude (a time of day)",
                              .found = "none",
                              .message = "a geodetic anchor needs the scene's geodetic origin"});
      const double lat0 = planet->origin->latitude_deg, lon0 = planet->origin->longitude_deg;
      double dlon = std::remainder(t.longitude_deg - lon0, 360.0);
      return {glm::radians(dlon) * std::cos(glm::radians(lat0)) * kEarthRadiusM,
              glm::radians(t.latitude_deg - lat0) * kEarthRadiusM, t.height_m};
    }
  }
  return {};
}

void add_light_term(World& world) {
  world.resource<LightEnvironment>().add(LightTerm{
      .name = "terrain.cascades",
      .include = "terrain/light_term.glsl",
      .light_visibility = "terrain_light_visibility",
      .textures = {"terrain.shadow_atlas"},
      .blocks = {"terrain.cascades"},
      .bind = [&world](const LightEnvironment& env) {
        TerrainCache& cache = world.resource<TerrainCache>();
        env.bind_block("terrain.cascades", cache.cascade_buffer, &cache.cascade_block,
                       sizeof(cache.cascade_block));
        if (cache.shadow_atlas) glBindTextureUnit(env.unit("terrain.shadow_atlas"), cache.shadow_atlas->id());
      },
      // The block as this frame set it, and the atlas's drawings: a frame that draws it again counts
      // as changed in the next (its draw is recorded when it runs).
      .state = [&world] {
        const TerrainCache& cache = world.resource<TerrainCache>();
        return fnv1a_64_of(
            cache.cascade_block,
            fnv1a_64_of(cache.cascade_draws, fnv1a_64_of(uintptr_t(cache.shadow_atlas.get()))));
      }});
}

namespace {

// Each terrain placed in the scene, with the chunks the view draws (their levels chosen, those outside
// the view culled) and those that cast shadows; each drawn chunk's pixels go into `covered` and into
// the frame's geometry.
std::vector<Placed> place_terrains(World& world, FrameTargets& frame, PixelRect& covered) {
  auto& rc = world.resource<RenderContext>();
  auto& cache = world.resource<TerrainCache>();
  const FrameView& view = rc.view;
  const double pixels_per_radian = view.height / view.vertical_fov_rad;
  // The scene's planet when a module set it (the atmosphere's), else each terrain's own.
  const PlanetFrame* planet = world.find_resource<PlanetFrame>();
  const std::optional<double> planet_radius_m =
      planet && planet->from_scene ? std::optional<double>(planet->radius_m) : std::nullopt;
  std::vector<Placed> placed;
  world.registry().each<Terrain>([&](Entity, Terrain& t) {
    Placed p;
    p.gpu = &cache.get(t);
    p.anchor_m = anchor_position(world, t);
    float h = glm::radians(t.heading_deg);
    // Heading turns the model clockwise seen from above (x east, y north).
    p.rotation = glm::mat3(glm::vec3(std::cos(h), -std::sin(h), 0), glm::vec3(std::sin(h), std::cos(h), 0),
                           glm::vec3(0, 0, 1));
    double radius_m = planet_radius_m ? *planet_radius_m : t.planet_radius_km * 1000.0;
    p.inverse_two_radius = t.follow_curvature ? float(0.5 / radius_m) : 0.0f;
    p.lod_pixel_error = t.lod_pixel_error;
    const glm::vec3 rel = glm::vec3(p.anchor_m - view.camera_position_m);
    const uint64_t placement =
        fnv1a_64_of(p.inverse_two_radius,
                    fnv1a_64_of(p.rotation, fnv1a_64_of(p.anchor_m, fnv1a_64(t.file, uintptr_t(p.gpu)))));
    for (const Chunk& c : p.gpu->mesh.chunks) {
      // Chunk box, camera-relative (rotation applied to the corners' hull; curvature lowers it a little).
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (int i = 0; i < 8; ++i) {
        glm::vec3 corner = p.rotation * glm::vec3(i & 1 ? c.max.x : c.min.x, i & 2 ? c.max.y : c.min.y,
                                                  i & 4 ? c.max.z : c.min.z);
        lo = glm::min(lo, corner), hi = glm::max(hi, corner);
      }
      glm::vec2 far_xy = glm::max(glm::abs(glm::vec2(lo) + glm::vec2(p.anchor_m)),
                                  glm::abs(glm::vec2(hi) + glm::vec2(p.anchor_m)));
      lo.z -= glm::dot(far_xy, far_xy) * p.inverse_two_radius;
      lo += rel, hi += rel;
      double distance = glm::length(glm::max(glm::max(lo, -hi), glm::vec3(0.0f)));
      int lod = select_lod(c, distance, pixels_per_radian, t.lod_pixel_error);
      int material = c.material < 0 ? int(p.gpu->materials.size()) - 1 : c.material;
      if (t.cast_shadows) p.casters.push_back({size_t(&c - p.gpu->mesh.chunks.data()), lo, hi});
      if (outside_view(view.view_projection, lo, hi)) continue;
      const LodRange& l = c.lods[size_t(lod)];
      // What this chunk writes to the depth: its level's triangles, placed (the view aside).
      const PixelRect pixels = screen_rect(view, lo, hi);
      covered.include(pixels);
      frame.add_geometry(pixels, fnv1a_64_of(l.first_index, fnv1a_64_of(l.index_count, placement)));
      p.draws.push_back({l.first_index, l.index_count, material, c.base_vertex, l.vertex_count});
      p.triangles += l.index_count / 3;
    }
    placed.push_back(std::move(p));
  });
  return placed;
}

// Shadows: cascades from the first terrain that casts them (one sun, one set of cascades), their
// block set, and a pass that draws those whose place, sun or casters changed since their last
// drawing. Returns the atlas's handle (invalid without shadows); `drawn`: whether a pass draws one.
ResourceHandle add_shadow_pass(SystemContext& sc, const std::shared_ptr<std::vector<Placed>>& placed,
                               bool& drawn) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  auto& cache = world.resource<TerrainCache>();
  std::optional<glm::vec3> sun = scene_sun_direction(world);
  if (sun && sun->z <= 0.0f) sun.reset();  // no shadows from a sun below the horizon
  const Terrain* shadow_settings = nullptr;
  world.registry().each<Terrain>([&](Entity, Terrain& t) {
    if (t.cast_shadows && !shadow_settings) shadow_settings = &t;
  });
  cache.cascade_block.shadows_on = 0;  // until a cascade is made this frame
  drawn = false;
  if (!sun || !shadow_settings) return {};
  const Cascades cs =
      make_cascades(rc.view, *sun, shadow_settings->shadow_distance_m, 20000.0f, cache.cascade_places);
  cache.cascade_places = TerrainCache::CascadePlaces{.centre_m = cs.centre_m, .extent_m = cs.extent_m};
  const int size = shadow_settings->shadow_map_size;
  Texture& atlas = cache.shadow_map(size);
  for (int i = 0; i < kShadowCascades; ++i) {
    gpu_blocks::TerrainCascade& c = cache.cascade_block.cascades[i];
    c.light_view_projection = cs.light_view_projection[size_t(i)];
    c.far_m = cs.far_m[size_t(i)];
    c.texel_m = cs.extent_m[size_t(i)] / float(size);
  }
  cache.cascade_block.shadows_on = 1;
  // Each cascade draws the casters its square sees, at the level whose error stays within the
  // terrain's pixel error in the cascade's texels: the far cascades draw coarse levels.
  for (Placed& p : *placed)
    for (int i = 0; i < kShadowCascades; ++i) {
      const double texels_per_m = size / double(cs.extent_m[size_t(i)]);
      for (const Caster& k : p.casters) {
        if (outside_view(cs.light_view_projection[size_t(i)], k.lo, k.hi)) continue;
        const Chunk& c = p.gpu->mesh.chunks[k.chunk];
        const LodRange& l = c.lods[size_t(select_lod(c, 1.0, texels_per_m, p.lod_pixel_error))];
        const int material = c.material < 0 ? int(p.gpu->materials.size()) - 1 : c.material;
        p.shadow_draws[size_t(i)].push_back(
            {l.first_index, l.index_count, material, c.base_vertex, l.vertex_count});
      }
    }
  const ResourceHandle shadow_handle = sc.graph->import("terrain.shadow_atlas", atlas);
  // A cascade whose place, sun and casters are those of its last drawing keeps its depths.
  std::array<std::string, kShadowCascades> inputs;
  std::vector<int> stale;
  for (int i = 0; i < kShadowCascades; ++i) {
    inputs[size_t(i)] = cascade_inputs(cs, i, *sun, *placed, size);
    if (inputs[size_t(i)] != cache.cascade_inputs[size_t(i)]) stale.push_back(i);
  }
  drawn = !stale.empty();
  if (drawn)
    sc.graph->add_pass(
        "terrain.shadows", [&](PassBuilder& b) { b.write(shadow_handle); },
        [placed, light_view_projection = cs.light_view_projection, shadow_handle, size, &rc, &cache,
         inputs = std::move(inputs), stale](PassContext& pc) {
          draw_shadow_cascades(pc.texture(shadow_handle), *placed, light_view_projection, size, stale,
                               inputs, rc, cache);
        });
  return shadow_handle;
}

}  // namespace

void terrain_system(SystemContext& sc) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  auto& cache = world.resource<TerrainCache>();
  const FrameView& view = rc.view;
  // The frame's depth holds no other geometry yet: a kept terrain's depth can replace it whole.
  const bool depth_empty = sc.targets->geometry.empty();
  SurfaceDraw surface_draw;  // covered: every pixel the drawn chunks may cover
  auto placed =
      std::make_shared<std::vector<Placed>>(place_terrains(world, *sc.targets, surface_draw.covered));

  const FrameTargets targets = *sc.targets;
  bool cascades_drawn = false;
  const ResourceHandle shadow_handle = add_shadow_pass(sc, placed, cascades_drawn);
  // A still view under still light draws the same terrain again, bit for bit: while what it is drawn
  // from stays the same (and no cascade is drawn this frame: its drawing is not yet in the light's
  // state), the frame takes the colour and depth drawn last, a copy instead of 110k triangles shaded.
  std::optional<uint64_t> inputs;
  if (depth_empty && !cascades_drawn) inputs = view_inputs(*placed, rc, world.resource<LightEnvironment>());
  const bool keep = inputs && *inputs == cache.kept_inputs && cache.kept_color;
  if (keep) {
    sc.graph->add_pass(
        "terrain",
        [&](PassBuilder& b) {
          b.read(targets.color);
          b.write(targets.color);
          b.write(targets.depth);
        },
        [targets, &rc, &cache](PassContext& pc) {
          draw_kept_terrain(pc.texture(targets.color), pc.texture(targets.depth), rc, cache);
        });
    return;
  }

  // Two passes: the surface (each material's inputs per pixel, with the depth), then its light, once
  // per pixel. Shading in the first pass would run the light for whole quads and blocks around
  // triangles of a pixel or two: several times the pixels the terrain covers on a software rasteriser.
  // The materials' own light goes into the frame's colour first, only where a drawn one has any.
  for (const Placed& p : *placed)
    for (const Draw& d : p.draws) {
      const GpuMaterial& m = p.gpu->materials[size_t(d.material)];
      surface_draw.emissive = surface_draw.emissive || m.emissive != glm::vec3(0.0f);
      surface_draw.own_transforms = surface_draw.own_transforms || m.own_transforms();
    }
  const ResourceHandle surface =
      sc.graph->create("terrain.surface", TextureDesc{.width = view.width,
                                                      .height = view.height,
                                                      .format = TextureFormat::rgba32ui,
                                                      .linear_filter = false});
  sc.graph->add_pass(
      "terrain",
      [&](PassBuilder& b) {
        b.read(targets.color);
        b.write(targets.color);
        b.read(targets.depth);
        b.write(targets.depth);
        b.write(surface);
      },
      [placed, targets, surface_draw, &rc, &cache, surface](PassContext& pc) {
        ++cache.view_draws;
        draw_surface(pc.texture(targets.color), pc.texture(surface), pc.texture(targets.depth), *placed,
                     surface_draw, rc);
      });
  sc.graph->add_pass(
      "terrain.light",
      [&](PassBuilder& b) {
        b.read(targets.color);
        b.write(targets.color);
        b.read(targets.depth);
        b.read(surface);
        if (shadow_handle.valid()) b.read(shadow_handle);
      },
      [targets, surface, surface_draw, &rc, &world, &cache, inputs](PassContext& pc) {
        draw_surface_light(pc.texture(targets.color), pc.texture(targets.depth), pc.texture(surface),
                           surface_draw, inputs, rc, world, cache);
      });
}

}  // namespace welkin::terrain
