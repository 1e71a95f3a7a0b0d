#include "welkin/gfx/debug_content.h"

#include <cmath>
#include <cstdint>
#include <glm/gtc/constants.hpp>
#include <map>
#include <vector>

#include "default_lights_block.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/shared_state.h"

namespace welkin {

void describe(TypeBuilder<Backdrop>& t) {
  t.tooltip("Gradient sky stand-in and orientation grid (test pattern)");
  t.field("zenith_color", &Backdrop::zenith_color).color().range(0, 1);
  t.field("horizon_color", &Backdrop::horizon_color).color().range(0, 1);
  t.field("ground_color", &Backdrop::ground_color).color().range(0, 1);
  t.field("luminance", &Backdrop::luminance).unit("cd/m^2").range(0, 1e9);
  t.field("grid", &Backdrop::grid).tooltip("Draw a 10-degree azimuth/elevation grid");
}

void describe(TypeBuilder<DirectionalLight>& t) {
  t.field("azimuth_deg", &DirectionalLight::azimuth_deg)
      .unit("deg")
      .range(-360, 360)
      .tooltip("Clockwise from north");
  t.field("elevation_deg", &DirectionalLight::elevation_deg).unit("deg").range(-90, 90);
  t.field("color", &DirectionalLight::color).color().range(0, 1);
  t.field("illuminance_lux", &DirectionalLight::illuminance_lux).unit("lx").range(0, 2e5);
  t.field("ambient_fraction", &DirectionalLight::ambient_fraction).range(0, 1);
}

void describe(TypeBuilder<DebugShape>& t) {
  t.field("shape", &DebugShape::shape).values({{"sphere", 0}, {"box", 1}});
  t.field("position_m", &DebugShape::position_m).unit("m").range(-1e9, 1e9);
  t.field("size_m", &DebugShape::size_m)
      .unit("m")
      .range(1e-3, 1e7)
      .tooltip("Sphere: radius in x; box: half extents");
  t.field("albedo", &DebugShape::albedo).color().range(0, 1);
}

glm::dvec3 direction_from_azimuth_elevation(double az, double el) {
  double a = glm::radians(az), e = glm::radians(el);
  return {std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), std::sin(e)};
}

namespace {

void backdrop_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  Entity e = reg.first<Backdrop>();
  Backdrop b = *reg.get<Backdrop>(e);
  auto& rc = sc.world.resource<RenderContext>();
  const FrameTargets t = *sc.targets;
  sc.graph->add_pass(
      "backdrop",
      [&](PassBuilder& pb) {
        pb.read(t.color);
        pb.write(t.color);
        pb.read(t.depth);
      },
      [&rc, b, t](PassContext& pc) {
        Framebuffer fb(&pc.texture(t.color), &pc.texture(t.depth));
        fb.bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GEQUAL);  // only where nothing nearer was drawn (depth still 0 = infinity)
        glDepthMask(GL_FALSE);
        const Program& p = rc.shaders.graphics("fullscreen.vert", "backdrop.frag");
        p.use();
        p.set("u_inverse_view_projection", rc.view.inverse_view_projection);
        p.set("u_zenith", b.zenith_color * b.luminance);
        p.set("u_horizon", b.horizon_color * b.luminance);
        p.set("u_ground", b.ground_color * b.luminance);
        p.set("u_grid", b.grid ? 1 : 0);
        rc.draw_fullscreen_triangle();
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
      });
}

// Slices of a sphere's latitude-longitude grid (stacks: half as many), from 8 to 64, enough that a
// facet's chord lies within a quarter of a pixel of the sphere on screen; -1 when it is wholly behind the
// camera.
int sphere_slices(const FrameView& view, const glm::vec3& centre, float radius) {
  if (glm::dot(centre, view.forward) < -radius) return -1;
  const float distance = std::max(glm::length(centre) - radius, view.near_m);
  const float radius_px =
      radius / distance * (0.5f * float(view.height)) / std::tan(0.5f * view.vertical_fov_rad);
  if (!(radius_px > 0.25f)) return 8;
  // The sagitta of a facet, r (1 - cos(pi / slices)), at most a quarter of a pixel.
  const float slices = 3.14159265f / std::acos(std::max(1.0f - 0.25f / radius_px, -1.0f));
  return std::clamp(2 * int(std::ceil(slices * 0.5f)), 8, 64);
}

// The spheres' grids as indexed triangles, an index buffer per slice count: llvmpipe shades each
// vertex of an indexed batch once, where a plain triangle list shades it once per corner (six times).
struct DebugShapeMeshes {
  static constexpr std::string_view kTypeName = "core.DebugShapeMeshes";
  GlVertexArrayName vao;
  std::map<int, Buffer> sphere_indices;
};

// Vertex (i, j) of the grid is j (slices + 1) + i; two counter-clockwise triangles per quad (seen
// from outside), as debug_shape.vert expects.
const Buffer& sphere_indices(DebugShapeMeshes& meshes, int slices) {
  auto it = meshes.sphere_indices.find(slices);
  if (it != meshes.sphere_indices.end()) return it->second;
  const int stacks = slices / 2, row = slices + 1;
  std::vector<uint16_t> indices;
  indices.reserve(size_t(slices) * size_t(stacks) * 6);
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const uint16_t v00 = uint16_t(j * row + i), v10 = uint16_t(v00 + 1), v01 = uint16_t(v00 + row),
                     v11 = uint16_t(v01 + 1);
      indices.insert(indices.end(), {v00, v10, v11, v00, v11, v01});
    }
  return meshes.sphere_indices.emplace(slices, Buffer(indices.size() * sizeof(uint16_t), indices.data()))
      .first->second;
}

void debug_shape_system(SystemContext& sc) {
  Registry& reg = sc.world.registry();
  auto& rc = sc.world.resource<RenderContext>();
  std::vector<DebugShape> shapes;
  reg.each<DebugShape>([&](Entity, DebugShape& s) { shapes.push_back(s); });
  for (const DebugShape& s : shapes) {
    const glm::vec3 rel = glm::vec3(s.position_m - rc.view.camera_position_m);
    const glm::vec3 half = s.shape == ShapeKind::sphere ? glm::vec3(s.size_m.x) : s.size_m;
    sc.targets->add_geometry(screen_rect(rc.view, rel - glm::abs(half), rel + glm::abs(half)),
                             fnv1a_64_of(s.size_m, fnv1a_64_of(s.position_m, fnv1a_64_of(int(s.shape)))));
  }
  const FrameTargets t = *sc.targets;
  sc.graph->add_pass(
      "debug_shapes",
      [&](PassBuilder& pb) {
        pb.read(t.color);
        pb.write(t.color);
        pb.read(t.depth);
        pb.write(t.depth);
      },
      [&rc, &world = sc.world, shapes, t](PassContext& pc) {
        Framebuffer fb(&pc.texture(t.color), &pc.texture(t.depth));
        fb.bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glEnable(GL_CULL_FACE);
        const Program& p = rc.shaders.graphics("debug_shape.vert", "debug_shape.frag");
        p.use();
        p.set("u_view_projection", rc.view.view_projection);
        world.resource<LightEnvironment>().bind();
        auto& meshes = world.resource<DebugShapeMeshes>();
        if (!meshes.vao) {
          GLuint vao = 0;
          glCreateVertexArrays(1, &vao);
          meshes.vao = GlVertexArrayName(vao);
        }
        for (const DebugShape& s : shapes) {
          // Camera-relative in double, then to float: precision independent of distance from the origin.
          glm::vec3 rel = glm::vec3(s.position_m - rc.view.camera_position_m);
          const int slices = s.shape == ShapeKind::sphere ? sphere_slices(rc.view, rel, s.size_m.x) : 0;
          if (slices < 0) continue;  // wholly behind the camera
          p.set("u_center", rel);
          p.set("u_size", s.size_m);
          p.set("u_albedo", s.albedo);
          p.set("u_shape", int(s.shape));
          p.set("u_slices", slices);
          // Spheres: the grid's vertices, indexed; boxes: 36 vertices. Both generated in the shader.
          if (s.shape == ShapeKind::sphere) {
            const Buffer& indices = sphere_indices(meshes, slices);
            glVertexArrayElementBuffer(meshes.vao.id(), indices.id());
            glBindVertexArray(meshes.vao.id());
            glDrawElements(GL_TRIANGLES, GLsizei(indices.size() / sizeof(uint16_t)), GL_UNSIGNED_SHORT,
                           nullptr);
          } else {
            glBindVertexArray(rc.empty_vao.id());
            glDrawArrays(GL_TRIANGLES, 0, 36);
          }
        }
        glBindVertexArray(rc.empty_vao.id());
        glDisable(GL_CULL_FACE);
      });
}

}  // namespace

// The scene's first core.DirectionalLight (or its defaults) as welkin/default_lights.glsl's block.
DefaultLightsBlock default_lights_block(World& world) {
  DirectionalLight light;
  const Registry& reg = world.registry();
  if (const ComponentPool* pool = reg.pool(type_id<DirectionalLight>()); pool && !pool->empty())
    light = *reg.get<DirectionalLight>(pool->entities()[0]);
  DefaultLightsBlock block{};
  block.direction = glm::vec3(direction_from_azimuth_elevation(light.azimuth_deg, light.elevation_deg));
  block.sky_fraction = light.ambient_fraction;
  block.illuminance_lux = light.color * light.illuminance_lux;
  return block;
}

// Without an atmosphere the built-in light stands in for the sun: it follows the time of day's
// ephemeris when the scene has one (dimmed by eclipses, off at night, ground illuminance).
void directional_light_system(SystemContext& sc) {
  const LightSource& sun = sc.world.resource<LightSources>().ephemeris.sun;
  Registry& reg = sc.world.registry();
  if (!sun.present) return;
  DirectionalLight& light = *reg.get<DirectionalLight>(reg.first<DirectionalLight>());
  light.azimuth_deg = float(sun.azimuth_deg);
  light.elevation_deg = float(sun.elevation_deg);
  const double illuminance = sun.illuminance_lux * sun.visible_fraction;
  light.illuminance_lux =
      float(sun.elevation_deg > 0 ? illuminance * std::sin(sun.elevation_deg * M_PI / 180.0) : 0.0);
}

void add_default_light_term(World& world) {
  auto buffer = std::make_shared<std::unique_ptr<Buffer>>();
  world.resource<LightEnvironment>().add(LightTerm{
      .name = "core.default_lights",
      .include = "welkin/default_lights.glsl",
      .lights = "default",
      .priority = 0,
      .blocks = {"core.default_lights"},
      .bind = [&world, buffer](const LightEnvironment& env) {
        const DefaultLightsBlock data = default_lights_block(world);
        env.bind_block("core.default_lights", *buffer, &data, sizeof(data));
      },
      .state = [&world] { return fnv1a_64_of(default_lights_block(world)); }});
}

void register_debug_content(ModuleContext& ctx) {
  add_default_light_term(ctx.world());
  ctx.component<Backdrop>();
  ctx.component<DirectionalLight>();
  ctx.component<DebugShape>();
  ctx.system({.name = "core.directional_light", .stage = Stage::complete_shared_state,
              .writes = {type_id<DirectionalLight>()}, .run = directional_light_system});
  ctx.system({.name = "core.backdrop",
              .stage = Stage::geometry,
              .reads = {type_id<Backdrop>()},
              .run = backdrop_system});
  ctx.system({.name = "core.debug_shapes", .stage = Stage::geometry, .reads = {type_id<DebugShape>()},
              .optional_reads = {type_id<DirectionalLight>()}, .run = debug_shape_system});
}

}  // namespace welkin
