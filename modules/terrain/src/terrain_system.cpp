// Render system of the terrain module: places each terrain, picks chunk levels of detail, culls
// chunks outside the view, and draws them with the runtime's PBR shading into colour and depth.
#include <cmath>

#include "terrain_gpu.h"
#include "terrain_system.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/field_path.h"

namespace welkin::terrain {

namespace {

// A scalar field of the first entity with `component`, when the scene has one (reached through
// reflection: the terrain depends on no other module).
std::optional<double> scene_scalar(World& world, std::string_view component, std::string_view field) {
  const ComponentInfo* info = world.modules().component(component);
  if (!info) return std::nullopt;
  const ComponentPool* pool = world.registry().pool(info->type->id);
  if (!pool || pool->empty()) return std::nullopt;
  return resolve_field(*info->type, world.registry().get(pool->entities()[0], info->type->id), field).get_scalar();
}

constexpr double kEarthRadiusM = 6371008.8;  // mean radius, for geodetic offsets

struct Draw {
  uint32_t first, count;
  int material;
};

struct Placed {
  GpuTerrain* gpu;
  glm::dvec3 anchor_m;  // model origin in the scene frame
  glm::mat3 rotation;   // heading
  float inverse_two_radius;
  std::vector<Draw> draws;
  size_t triangles = 0;
};

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

}  // namespace

glm::dvec3 anchor_position(World& world, const Terrain& t) {
  switch (t.anchor) {
    case Anchor::scene_origin: return {0.0, 0.0, t.height_m};
    case Anchor::offset: return t.offset_m + glm::dvec3(0.0, 0.0, t.height_m);
    case Anchor::geodetic: {
      auto lat0 = scene_scalar(world, "timeofday.TimeOfDay", "latitude_deg");
      auto lon0 = scene_scalar(world, "timeofday.TimeOfDay", "longitude_deg");
      if (!lat0 || !lon0)
        throw Error(ErrorInfo{.path = "terrain.Terrain/anchor", .expected = "a timeofday.TimeOfDay giving the scene origin's latitude and longitude",
                              .found = "none", .message = "a geodetic anchor needs the scene's geodetic origin"});
      double dlon = std::remainder(t.longitude_deg - *lon0, 360.0);
      return {glm::radians(dlon) * std::cos(glm::radians(*lat0)) * kEarthRadiusM,
              glm::radians(t.latitude_deg - *lat0) * kEarthRadiusM, t.height_m};
    }
  }
  return {};
}

void terrain_system(SystemContext& sc) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  auto& cache = world.resource<TerrainCache>();
  const FrameView& view = rc.view;
  const double pixels_per_radian = view.height / view.vertical_fov_rad;
  double planet_radius_km = 0.0;
  if (auto r = scene_scalar(world, "atmosphere.Atmosphere", "bottom_radius_km")) planet_radius_km = *r;

  auto placed = std::make_shared<std::vector<Placed>>();
  world.registry().each<Terrain>([&](Entity, Terrain& t) {
    Placed p;
    p.gpu = &cache.get(t);
    p.anchor_m = anchor_position(world, t);
    float h = glm::radians(t.heading_deg);
    // Heading turns the model clockwise seen from above (x east, y north).
    p.rotation = glm::mat3(glm::vec3(std::cos(h), -std::sin(h), 0), glm::vec3(std::sin(h), std::cos(h), 0), glm::vec3(0, 0, 1));
    double radius_m = (planet_radius_km > 0 ? planet_radius_km : t.planet_radius_km) * 1000.0;
    p.inverse_two_radius = t.follow_curvature ? float(0.5 / radius_m) : 0.0f;
    const glm::vec3 rel = glm::vec3(p.anchor_m - view.camera_position_m);
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
      if (outside_view(view.view_projection, lo, hi)) continue;
      double distance = glm::length(glm::max(glm::max(lo, -hi), glm::vec3(0.0f)));
      const LodRange& l = c.lods[size_t(select_lod(c, distance, pixels_per_radian, t.lod_pixel_error))];
      p.draws.push_back({l.first_index, l.index_count, c.material < 0 ? int(p.gpu->materials.size()) - 1 : c.material});
      p.triangles += l.index_count / 3;
    }
    placed->push_back(std::move(p));
  });

  const FrameTargets targets = *sc.targets;
  const Registry* reg = &world.registry();
  sc.graph->add_pass("terrain", [&](PassBuilder& b) {
    b.read(targets.color);
    b.write(targets.color);
    b.read(targets.depth);
    b.write(targets.depth);
  }, [placed, targets, &rc, reg](PassContext& pc) {
    Framebuffer fb(&pc.texture(targets.color), &pc.texture(targets.depth));
    fb.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    const Program& prog = rc.shaders.graphics("terrain/terrain.vert", "terrain/terrain.frag");
    prog.use();
    set_default_light_uniforms(prog, *reg);
    prog.set("u_view_projection", rc.view.view_projection);
    for (const Placed& p : *placed) {
      prog.set("u_anchor_relative", glm::vec3(p.anchor_m - rc.view.camera_position_m));
      prog.set("u_anchor_xy", glm::vec2(p.anchor_m));
      prog.set("u_rotation", p.rotation);
      prog.set("u_inverse_two_radius", p.inverse_two_radius);
      glBindVertexArray(p.gpu->vao.id());
      int bound = -2;
      for (const Draw& d : p.draws) {
        if (d.material != bound) {
          const GpuMaterial& m = p.gpu->materials[size_t(d.material)];
          prog.set("u_base_color_factor", m.base_color_factor);
          prog.set("u_metallic", m.metallic);
          prog.set("u_roughness", m.roughness);
          prog.set("u_emissive", m.emissive);
          prog.set("u_uv_transform", m.uv_transform);
          prog.set("u_has_base_color", m.base_color ? 1 : 0);
          prog.set("u_has_metallic_roughness", m.metallic_roughness ? 1 : 0);
          prog.set("u_has_occlusion", m.occlusion ? 1 : 0);
          glBindTextureUnit(0, m.base_color.id());
          glBindTextureUnit(1, m.metallic_roughness.id());
          glBindTextureUnit(2, m.occlusion.id());
          bound = d.material;
        }
        glDrawElements(GL_TRIANGLES, GLsizei(d.count), GL_UNSIGNED_INT, reinterpret_cast<const void*>(uintptr_t(d.first) * 4));
      }
    }
    glDisable(GL_CULL_FACE);
  });
}

}  // namespace welkin::terrain
