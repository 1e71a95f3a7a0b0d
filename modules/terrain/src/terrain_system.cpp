// Render system of the terrain module: places each terrain, picks chunk levels of detail, culls
// chunks outside the view, draws the cascaded shadow maps, then the chunks' surface (depth and each
// pixel's material inputs) and its light (the runtime's PBR shading, once per pixel); a still view
// takes the terrain it drew last.
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "terrain_gpu.h"
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
  const glm::dvec3 f = -glm::dvec3(sun), s = glm::normalize(glm::cross(f, glm::dvec3(up))), u = glm::cross(s, f);
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
    glm::dvec3 snapped = s * snap(glm::dot(world, s)) + u * snap(glm::dot(world, u)) + f * snap(glm::dot(world, f));
    radius += float(step);
    if (previous && previous->extent_m[size_t(i)] == 2.0f * radius) {
      const glm::dvec3 d = world - previous->centre_m[size_t(i)];
      if (std::abs(glm::dot(d, s)) <= step && std::abs(glm::dot(d, u)) <= step && std::abs(glm::dot(d, f)) <= step)
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

struct Draw {
  uint32_t first, count;
  int material;
  uint32_t base_vertex;
  uint32_t vertex_count;  // the level's vertices: the first of its chunk's
};

// One chunk's level: 16-bit indices counted from the chunk's first vertex, and the range of vertices
// they use (a rasteriser that shades a draw's whole range then shades only the level's).
void draw_elements(const Draw& d) {
  glDrawRangeElementsBaseVertex(GL_TRIANGLES, 0, std::max(d.vertex_count, 1u) - 1, GLsizei(d.count), GL_UNSIGNED_SHORT,
                                reinterpret_cast<const void*>(uintptr_t(d.first) * sizeof(uint16_t)), GLint(d.base_vertex));
}

// A chunk that casts shadows, with its camera-relative bounds (culled against each cascade).
struct Caster {
  size_t chunk;
  glm::vec3 lo, hi;
};

struct Placed {
  GpuTerrain* gpu;
  glm::dvec3 anchor_m;  // model origin in the scene frame
  glm::mat3 rotation;   // heading
  float inverse_two_radius;
  std::vector<Draw> draws;
  float lod_pixel_error;
  std::vector<Caster> casters;  // every chunk (casters outside the view still cast)
  std::array<std::vector<Draw>, 3> shadow_draws;  // per cascade: the casters it sees, at its level
  size_t triangles = 0;
};

// Where a terrain sits relative to the camera, for terrain.vert (view and shadow passes alike).
void bind_placement(const Program& prog, const Placed& p, const FrameView& view) {
  prog.set("u_anchor_relative", glm::vec3(p.anchor_m - view.camera_position_m));
  prog.set("u_anchor_xy", glm::vec2(p.anchor_m));
  prog.set("u_rotation", p.rotation);
  prog.set("u_inverse_two_radius", p.inverse_two_radius);
  glBindVertexArray(p.gpu->vao.id());
}

bool outside_view(const glm::mat4& view_projection, const glm::vec3& lo, const glm::vec3& hi) {
  int out[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 8; ++i) {
    glm::vec4 c = view_projection * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
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
std::string cascade_inputs(const Cascades& c, int i, const glm::vec3& sun, const std::vector<Placed>& placed, int size) {
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
std::optional<uint64_t> view_inputs(const std::vector<Placed>& placed, const RenderContext& rc, const LightEnvironment& env) {
  const std::optional<uint64_t> light = env.state();
  if (!light) return std::nullopt;
  const FrameView& v = rc.view;
  uint64_t h = fnv1a_64_of(*light, fnv1a_64_of(env.version(), fnv1a_64_of(env.moon_lights_surfaces())));
  h = fnv1a_64_of(v.view_projection, fnv1a_64_of(v.camera_position_m, h));
  const int frame[3] = {v.width, v.height, int(rc.full_precision)};
  h = fnv1a_64_of(frame, fnv1a_64_of(rc.shaders.environment_version(), h));
  for (const Placed& p : placed) {
    h = fnv1a_64_of(p.inverse_two_radius, fnv1a_64_of(p.rotation, fnv1a_64_of(p.anchor_m, fnv1a_64_of(p.gpu, h))));
    h = fnv1a_64(std::string_view(reinterpret_cast<const char*>(p.draws.data()), p.draws.size() * sizeof(Draw)), h);
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
                              .found = "none", .message = "a geodetic anchor needs the scene's geodetic origin"});
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
        env.bind_block("terrain.cascades", cache.cascade_buffer, &cache.cascade_block, sizeof(cache.cascade_block));
        if (cache.shadow_atlas) glBindTextureUnit(env.unit("terrain.shadow_atlas"), cache.shadow_atlas->id());
      },
      // The block as this frame set it, and the atlas's drawings: a frame that draws it again counts
      // as changed in the next (its draw is recorded when it runs).
      .state = [&world] {
        const TerrainCache& cache = world.resource<TerrainCache>();
        return fnv1a_64_of(cache.cascade_block,
                           fnv1a_64_of(cache.cascade_draws, fnv1a_64_of(uintptr_t(cache.shadow_atlas.get()))));
      }});
}

void terrain_system(SystemContext& sc) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  auto& cache = world.resource<TerrainCache>();
  const FrameView& view = rc.view;
  // The frame's depth holds no other geometry yet: a kept terrain's depth can replace it whole.
  const bool depth_empty = sc.targets->geometry.empty();
  const double pixels_per_radian = view.height / view.vertical_fov_rad;
  // The scene's planet when a module set it (the atmosphere's), else each terrain's own.
  const PlanetFrame* planet = world.find_resource<PlanetFrame>();
  const std::optional<double> planet_radius_m =
      planet && planet->from_scene ? std::optional<double>(planet->radius_m) : std::nullopt;

  auto placed = std::make_shared<std::vector<Placed>>();
  PixelRect covered;  // every pixel the drawn chunks may cover
  world.registry().each<Terrain>([&](Entity, Terrain& t) {
    Placed p;
    p.gpu = &cache.get(t);
    p.anchor_m = anchor_position(world, t);
    float h = glm::radians(t.heading_deg);
    // Heading turns the model clockwise seen from above (x east, y north).
    p.rotation = glm::mat3(glm::vec3(std::cos(h), -std::sin(h), 0), glm::vec3(std::sin(h), std::cos(h), 0), glm::vec3(0, 0, 1));
    double radius_m = planet_radius_m ? *planet_radius_m : t.planet_radius_km * 1000.0;
    p.inverse_two_radius = t.follow_curvature ? float(0.5 / radius_m) : 0.0f;
    p.lod_pixel_error = t.lod_pixel_error;
    const glm::vec3 rel = glm::vec3(p.anchor_m - view.camera_position_m);
    const uint64_t placement = fnv1a_64_of(
        p.inverse_two_radius, fnv1a_64_of(p.rotation, fnv1a_64_of(p.anchor_m, fnv1a_64(t.file, uintptr_t(p.gpu)))));
    for (const Chunk& c : p.gpu->mesh.chunks) {
      // Chunk box, camera-relative (rotation applied to the corners' hull; curvature lowers it a little).
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (int i = 0; i < 8; ++i) {
        glm::vec3 corner = p.rotation * glm::vec3(i & 1 ? c.max.x : c.min.x, i & 2 ? c.max.y : c.min.y, i & 4 ? c.max.z : c.min.z);
        lo = glm::min(lo, corner), hi = glm::max(hi, corner);
      }
      glm::vec2 far_xy = glm::max(glm::abs(glm::vec2(lo) + glm::vec2(p.anchor_m)), glm::abs(glm::vec2(hi) + glm::vec2(p.anchor_m)));
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
      sc.targets->add_geometry(pixels, fnv1a_64_of(l.first_index, fnv1a_64_of(l.index_count, placement)));
      p.draws.push_back({l.first_index, l.index_count, material, c.base_vertex, l.vertex_count});
      p.triangles += l.index_count / 3;
    }
    placed->push_back(std::move(p));
  });

  const FrameTargets targets = *sc.targets;
  // Shadows: cascades from the first terrain that casts them (one sun, one set of cascades).
  std::optional<glm::vec3> sun = scene_sun_direction(world);
  if (sun && sun->z <= 0.0f) sun.reset();  // no shadows from a sun below the horizon
  const Terrain* shadow_settings = nullptr;
  world.registry().each<Terrain>([&](Entity, Terrain& t) {
    if (t.cast_shadows && !shadow_settings) shadow_settings = &t;
  });
  auto cascades = std::make_shared<std::optional<Cascades>>();
  ResourceHandle shadow_handle;
  cache.cascade_block.far_m.w = 0.0f;  // until a cascade is made this frame
  bool cascades_drawn = false;
  if (sun && shadow_settings) {
    *cascades = make_cascades(view, *sun, shadow_settings->shadow_distance_m, 20000.0f, cache.cascade_places);
    const Cascades& cs = **cascades;
    cache.cascade_places = TerrainCache::CascadePlaces{.centre_m = cs.centre_m, .extent_m = cs.extent_m};
    const int size = shadow_settings->shadow_map_size;
    Texture& atlas = cache.shadow_map(size);
    for (int i = 0; i < kShadowCascades; ++i) {
      cache.cascade_block.light_view_projection[i] = cs.light_view_projection[size_t(i)];
      cache.cascade_block.far_m[i] = cs.far_m[size_t(i)];
      cache.cascade_block.texel_m[i] = cs.extent_m[size_t(i)] / float(size);
    }
    cache.cascade_block.far_m.w = 1.0f;
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
          p.shadow_draws[size_t(i)].push_back({l.first_index, l.index_count, material, c.base_vertex, l.vertex_count});
        }
      }
    shadow_handle = sc.graph->import("terrain.shadow_atlas", atlas);
    // A cascade whose place, sun and casters are those of its last drawing keeps its depths.
    auto inputs = std::make_shared<std::array<std::string, kShadowCascades>>();
    std::vector<int> stale;
    for (int i = 0; i < kShadowCascades; ++i) {
      (*inputs)[size_t(i)] = cascade_inputs(cs, i, *sun, *placed, size);
      if ((*inputs)[size_t(i)] != cache.cascade_inputs[size_t(i)]) stale.push_back(i);
    }
    cascades_drawn = !stale.empty();
    if (cascades_drawn)
    sc.graph->add_pass("terrain.shadows", [&](PassBuilder& b) { b.write(shadow_handle); },
                       [placed, cascades, shadow_handle, size, &rc, &cache, inputs, stale](PassContext& pc) {
      Framebuffer fb(nullptr, &pc.texture(shadow_handle));
      fb.bind();
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
      glClearDepth(1.0);
      glEnable(GL_SCISSOR_TEST);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(2.0f, 4.0f);  // slope-scaled bias against self-shadowing acne
      const Program& prog = rc.shaders.graphics("terrain/terrain.vert", "terrain/depth.frag");
      prog.use();
      for (int i : stale) {
        glViewport(i * size, 0, size, size);
        glScissor(i * size, 0, size, size);
        glClear(GL_DEPTH_BUFFER_BIT);
        prog.set("u_view_projection", (**cascades).light_view_projection[size_t(i)]);
        for (const Placed& p : *placed) {
          bind_placement(prog, p, rc.view);
          for (const Draw& d : p.shadow_draws[size_t(i)]) draw_elements(d);
        }
        // Once drawn: a frame that failed before this draws it again.
        cache.cascade_inputs[size_t(i)] = (*inputs)[size_t(i)];
        ++cache.cascade_draws;
      }
      glDisable(GL_SCISSOR_TEST);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glDepthFunc(GL_GREATER);  // back to the frame's reversed-Z convention
      glClearDepth(0.0);
    });
  }
  // A still view under still light draws the same terrain again, bit for bit: while what it is drawn
  // from stays the same (and no cascade is drawn this frame: its drawing is not yet in the light's
  // state), the frame takes the colour and depth drawn last, a copy instead of 110k triangles shaded.
  std::optional<uint64_t> inputs;
  if (depth_empty && !cascades_drawn) inputs = view_inputs(*placed, rc, world.resource<LightEnvironment>());
  const bool keep = inputs && *inputs == cache.kept_inputs && cache.kept_color;
  if (keep) {
    sc.graph->add_pass("terrain", [&](PassBuilder& b) {
      b.read(targets.color);
      b.write(targets.color);
      b.write(targets.depth);
    }, [targets, &rc, &cache](PassContext& pc) {
      // The kept depth replaces the frame's; the kept colour goes where it holds terrain (the depth
      // test against a triangle at infinity passes exactly there); the sky stays elsewhere.
      const Texture& depth = pc.texture(targets.depth);
      copy_texture(*cache.kept_depth, depth);
      Framebuffer fb(&pc.texture(targets.color), &depth);
      fb.bind();
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_FALSE);
      glDisable(GL_BLEND);
      rc.shaders.graphics("fullscreen.vert", "copy.frag").use();
      glBindTextureUnit(0, cache.kept_color->id());
      rc.draw_fullscreen_triangle();
      glDepthMask(GL_TRUE);
      glDepthFunc(GL_GREATER);
    });
    return;
  }

  // Two passes: the surface (each material's inputs per pixel, with the depth), then its light, once
  // per pixel. Shading in the first pass would run the light for whole quads and blocks around
  // triangles of a pixel or two: several times the pixels the terrain covers on a software rasteriser.
  // The materials' own light goes into the frame's colour first, only where a drawn one has any.
  bool emissive = false, own_transforms = false;
  for (const Placed& p : *placed)
    for (const Draw& d : p.draws) {
      const GpuMaterial& m = p.gpu->materials[size_t(d.material)];
      emissive = emissive || m.emissive != glm::vec3(0.0f);
      own_transforms = own_transforms || m.own_transforms();
    }
  auto surface = std::make_shared<ResourceHandle>();
  sc.graph->add_pass("terrain", [&](PassBuilder& b) {
    b.read(targets.color);
    b.write(targets.color);
    b.read(targets.depth);
    b.write(targets.depth);
    *surface = b.create("terrain.surface", TextureDesc{.width = view.width, .height = view.height,
                                                       .format = TextureFormat::rgba32ui, .linear_filter = false});
  }, [placed, targets, surface, covered, emissive, own_transforms, &rc, &cache](PassContext& pc) {
    ++cache.view_draws;
    Framebuffer fb({&pc.texture(targets.color), &pc.texture(*surface)}, &pc.texture(targets.depth));
    fb.bind();
    // No terrain yet: the light pass skips what other geometry drew before (roughness 0).
    const GLuint none[4] = {0, 0, 0, 0};
    glEnable(GL_SCISSOR_TEST);
    glScissor(covered.x0, covered.y0, covered.x1 - covered.x0, covered.y1 - covered.y0);
    glClearBufferuiv(GL_COLOR, 1, none);
    glColorMaski(0, emissive, emissive, emissive, emissive);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);  // several draw buffers: no second source colour may be named
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    const Program& prog = rc.shaders.graphics("terrain/terrain.vert", "terrain/terrain.frag",
                                              {{"TERRAIN_TEXTURE_TRANSFORMS", own_transforms ? "1" : "0"}});
    prog.use();
    prog.set("u_view_projection", rc.view.view_projection);
    for (const Placed& p : *placed) {
      bind_placement(prog, p, rc.view);
      int bound = -2;
      for (const Draw& d : p.draws) {
        if (d.material != bound) {
          const GpuMaterial& m = p.gpu->materials[size_t(d.material)];
          prog.set("u_base_color_factor", m.base_color_factor);
          prog.set("u_metallic", m.metallic);
          prog.set("u_roughness", m.roughness);
          prog.set("u_emissive", m.emissive);
          prog.set("u_occlusion_strength", m.occlusion_strength);
          prog.set("u_uv_transform", m.uv_transforms[0]);
          prog.set("u_metallic_roughness_transform", m.uv_transforms[1]);
          prog.set("u_occlusion_transform", m.uv_transforms[2]);
          prog.set("u_emissive_transform", m.uv_transforms[3]);
          prog.set("u_has_base_color", m.base_color ? 1 : 0);
          prog.set("u_has_metallic_roughness", m.metallic_roughness ? 1 : 0);
          prog.set("u_has_occlusion", m.occlusion ? 1 : 0);
          prog.set("u_has_emissive", m.emissive_map ? 1 : 0);
          glBindTextureUnit(0, m.base_color.id());
          glBindTextureUnit(1, m.metallic_roughness.id());
          glBindTextureUnit(2, m.occlusion.id());
          glBindTextureUnit(3, m.emissive_map.id());
          bound = d.material;
        }
        draw_elements(d);
      }
    }
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
  });

  sc.graph->add_pass("terrain.light", [&](PassBuilder& b) {
    b.read(targets.color);
    b.write(targets.color);
    b.read(targets.depth);
    b.read(*surface);
    if (shadow_handle.valid()) b.read(shadow_handle);
  }, [targets, surface, covered, emissive, &rc, &world, &cache, inputs](PassContext& pc) {
    const Texture &color = pc.texture(targets.color), &depth = pc.texture(targets.depth);
    {
      // Depth attached read-only and read at the fragment's own texel (GL 4.5, 9.3.1); the triangle
      // at infinity passes GL_LESS only where something was drawn.
      Framebuffer fb(&color, &depth);
      fb.bind();
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_FALSE);
      glEnable(GL_SCISSOR_TEST);
      glScissor(covered.x0, covered.y0, covered.x1 - covered.x0, covered.y1 - covered.y0);
      if (emissive) {
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // onto the materials' own light
      }
      world.resource<LightEnvironment>().bind();
      const Program& prog = rc.shaders.graphics("fullscreen.vert", "terrain/light.frag");
      prog.use();
      prog.set("u_inverse_view_projection", rc.view.inverse_view_projection);
      glBindTextureUnit(0, depth.id());
      glBindTextureUnit(1, pc.texture(*surface).id());
      rc.draw_fullscreen_triangle();
      glDisable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ZERO);
      glDisable(GL_SCISSOR_TEST);
      glDepthMask(GL_TRUE);
      glDepthFunc(GL_GREATER);
    }
    // Recorded once drawn (a failed frame draws again); kept when drawn twice alike.
    if (inputs && *inputs == cache.drawn_inputs) {
      const TextureDesc color_desc = color.desc(), depth_desc = depth.desc();
      if (!cache.kept_color || !(cache.kept_color->desc() == color_desc)) cache.kept_color = std::make_unique<Texture>(color_desc);
      if (!cache.kept_depth || !(cache.kept_depth->desc() == depth_desc)) cache.kept_depth = std::make_unique<Texture>(depth_desc);
      copy_texture(color, *cache.kept_color);
      copy_texture(depth, *cache.kept_depth);
      cache.kept_inputs = *inputs;
    }
    cache.drawn_inputs = inputs.value_or(0);
  });
}

}  // namespace welkin::terrain
