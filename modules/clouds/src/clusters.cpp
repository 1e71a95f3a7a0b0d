// The mesh clusters (clouds.CloudClusters): one layer of the volumetric description drawn at mid
// range as instanced puffs. Each frame, compute passes place the clusters where the layer's weather
// and noise hold cloud (nearest first, up to the budget), give each puff the field's extinction,
// its light and the air in front of it, and sort the puffs far to near; one instanced draw then
// draws them at a fraction of the frame's size and records where they turn opaque, so that the march
// stops there; the march's composite lays both over the frame.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "welkin/assets/subdivision.h"
#include "clouds_gpu.h"
#include "clusters.h"
#include "density_field.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"

namespace welkin::clouds {

ClustersGpu::~ClustersGpu() {
  if (vao) glDeleteVertexArrays(1, &vao);
}

std::vector<glm::vec4> puff_proxy_mesh(int level) {
  assets::ControlMesh cube;
  for (int i = 0; i < 8; ++i)
    cube.positions.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
  cube.face_sizes.assign(6, 4);
  cube.face_indices = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
  const assets::RefinedMesh m = assets::refine(cube, {.levels = level,
                                                      .scheme = assets::SubdivScheme::catmull_clark,
                                                      .limit_surface = true,
                                                      .sharp_boundary_corners = false});
  // Onto the unit sphere, then pushed out until every face's plane clears it: the proxy encloses
  // the puff, whose surface the fragment shader finds exactly.
  std::vector<glm::vec3> p(m.positions.size());
  for (size_t i = 0; i < p.size(); ++i) p[i] = glm::normalize(m.positions[i]);
  float nearest = 1.0f;
  std::vector<glm::vec4> out;
  out.reserve(m.indices.size());
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    glm::vec3 a = p[m.indices[t]], b = p[m.indices[t + 1]], c = p[m.indices[t + 2]];
    glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    // Outward and counter-clockwise seen from outside (the draw keeps the far side).
    if (glm::dot(n, a + b + c) < 0.0f) std::swap(b, c), n = -n;
    nearest = std::min(nearest, glm::dot(n, a));
    out.insert(out.end(), {glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(c, 1.0f)});
  }
  const float scale = 1.0f / std::max(nearest, 1e-3f);
  for (glm::vec4& v : out) v = glm::vec4(glm::vec3(v) * scale, 1.0f);
  return out;
}

namespace {

// The points of each step at which the draw reads the layer's envelope to place the step's one sample
// of the field (clouds/puff.frag; docs/clouds-far.md, "The envelope's candidates"): at the switch,
// 160x90, 1 -> 4 took the per-pixel difference from 31.1% to 20.9%, and the draw's cost stayed
// within the march's other layers' saving (the field of the clusters' layer alone).
constexpr int kEnvelopeCandidates = 4;

const CloudClusters* first_clusters(World& world) {
  Registry& reg = world.registry();
  const Entity e = reg.first<CloudClusters>();
  return e.is_null() ? nullptr : reg.get<CloudClusters>(e);
}

// What placing a frame's puffs needs, taken when the pass is declared.
struct PuffPlacement {
  ShaderDefines field;
  PlacementGrid grid;
  int packed, n_clusters, n_puffs, order_size, count;
  glm::vec4 range;
  float density_scale;
  glm::vec3 light_dir;
  bool moon, sorted;
  uint32_t seed;
};

// The clusters' cells chosen, their puffs placed and (when sorted) ordered far to near.
void place_puffs(CloudsGpu& gpu, RenderContext& rc, World& world, const PuffPlacement& pp) {
  ClustersGpu& c = gpu.clusters;
  const PlacementGrid& grid = pp.grid;
  bind_field(gpu);
  world.resource<LightEnvironment>().bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, c.puffs->id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, c.order->id());
  // A cluster spreads over its cell: cells a cell beyond the ring's ends may hold some of it.
  const glm::vec4& range = pp.range;
  const glm::vec2 ring{range.x - 0.5f * range.y - float(grid.cell_m), range.z + float(grid.cell_m)};
  c.placement.choose(rc.shaders, pp.field, grid, pp.packed, pp.n_clusters, ring, pp.seed, /*in_view=*/true);
  const int invocations[2] = {pp.count, pp.order_size};
  for (int stage = 2; stage < 4; ++stage) {
    ShaderDefines d = pp.field;
    d["CLUSTERS_STAGE"] = std::to_string(stage);
    const Program& p = rc.shaders.compute("clouds/clusters_place.comp", d);
    set_placement_uniforms(p, grid, pp.seed);
    p.set("u_layer", pp.packed);
    p.set("u_clusters", pp.n_clusters);
    p.set("u_puffs", pp.n_puffs);
    p.set("u_range", range);
    p.set("u_density_scale", pp.density_scale);
    p.set("u_order_size", pp.order_size);
    p.set("u_light_dir", pp.light_dir);
    p.set("u_light", pp.moon ? 1 : 0);
    p.set("u_axis_up", grid.axis_up);
    dispatch_compute(p, group_count(invocations[stage - 2], 64), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  if (pp.sorted) sort_far_to_near(rc.shaders, pp.order_size);
}

}  // namespace

void clusters_system(SystemContext& sc) {
  World& world = sc.world;
  auto& gpu = world.resource<CloudsGpu>();
  ClustersGpu& cg = gpu.clusters;
  const CloudClusters* clusters = first_clusters(world);
  if (!clusters) return;
  check_component(*clusters);
  const VolumetricClouds& clouds =
      drawn_clouds(world.registry(), CloudClusters::kTypeName, clusters->layer, "clusters");
  const int packed = gpu.clusters_layer;
  const int count = clusters->clusters * clusters->puffs_per_cluster;
  cg.puff_count = 0;
  if (!gpu.has_layers || packed < 0 || count == 0) return;
  auto& rc = world.resource<RenderContext>();
  const FrameView& view = rc.view;

  const bool mesh = clusters->proxy == PuffProxy::mesh;
  // The proxy mesh, the grid's order and the buffers, made when their sizes change.
  if (mesh && cg.proxy_level != clusters->subdivision_level) {
    const std::vector<glm::vec4> triangles = puff_proxy_mesh(clusters->subdivision_level);
    cg.proxy = std::make_unique<Buffer>(triangles.size() * sizeof(glm::vec4), triangles.data());
    cg.proxy_vertices = int(triangles.size());
    cg.proxy_level = clusters->subdivision_level;
  }
  const CloudLayer& layer = clouds.layers[size_t(clusters->layer)];
  const PlacementGrid grid = placement_grid(gpu, view, layer, clusters->cell_m, clusters->far_m);
  const int order_size = next_power_of_two(count);
  cg.placement.ensure(grid.grid, clusters->clusters);
  ensure_buffer(cg.puffs, cg.puff_capacity, size_t(count) * sizeof(ClusterPuffGpu));
  ensure_buffer(cg.order, cg.order_capacity, size_t(order_size) * 2 * sizeof(uint32_t));
  const int width = std::max(1, int(std::ceil(view.width * clusters->resolution_scale)));
  const int height = std::max(1, int(std::ceil(view.height * clusters->resolution_scale)));

  const CloudsContext& ctx = gpu.context;
  const bool moon = gpu.block.moon_marched > 0.5f;
  const glm::vec3 light_dir = moon ? glm::vec3(0, 0, 1) : ctx.sun_direction;
  const PuffPlacement placement{
      .field = field_defines(gpu),
      .grid = grid,
      .packed = packed,
      .n_clusters = clusters->clusters,
      .n_puffs = clusters->puffs_per_cluster,
      .order_size = order_size,
      .count = count,
      .range = {gpu.clusters_near_m, clusters->crossfade_m, clusters->far_m, 0.0f},
      .density_scale = clusters->density_scale,
      .light_dir = light_dir,
      .moon = moon,
      .sorted = clusters->compositing == ClusterCompositing::sorted,
      .seed = uint32_t(clusters->seed)};
  CloudsGpu* gp = &gpu;
  cg.puff_count = count;

  RenderGraph& g = *sc.graph;
  g.add_pass(
      "clouds.clusters_place", [](PassBuilder& b) { b.side_effect(); },
      [gp, &rc, &world, placement](PassContext&) { place_puffs(*gp, rc, world, placement); });

  const FrameTargets t = *sc.targets;
  const int samples = clusters->samples;
  // The sun's light through the clouds' shadow map where the layer casts shadows into it.
  const bool shadow_map = !moon && layer.casts_shadow && gpu.shadow.cascade_count > 0;
  const FarCloudTargets targets = far_cloud_targets(g, width, height);
  g.add_pass(
      "clouds.clusters_draw",
      [&](PassBuilder& b) {
        b.read(t.depth);
        write_far_cloud_targets(b, targets);
      },
      [gp, &rc, &world, t, targets, count, grid, light_dir, samples, mesh, shadow_map, packed,
       range = placement.range, field = placement.field](PassContext& pc) {
        ClustersGpu& c = gp->clusters;
        const Framebuffer fb = begin_far_cloud_draw(pc, targets);
        if (mesh) {
          glEnable(GL_CULL_FACE);
          glCullFace(GL_FRONT);  // the far side: one fragment per pixel per puff, also from inside
        }
        if (!c.vao) glCreateVertexArrays(1, &c.vao);
        glBindVertexArray(c.vao);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, gp->frame_buffer->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, c.puffs->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, c.order->id());
        if (mesh) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, c.proxy->id());
        glBindTextureUnit(3, pc.texture(t.depth).id());
        // The sample count is compiled in: llvmpipe runs a loop of run-time length for its whole group
        // of pixels, and unrolls one of fixed length.
        // The puffs march their layer's field.
        bind_field(*gp);
        ShaderDefines d = field;
        for (const auto& [name, value] : light_model_defines(*gp)) d[name] = value;
        d["PUFF_PROXY_MESH"] = mesh ? "1" : "0";
        d["PUFF_SAMPLES"] = std::to_string(samples);
        d["PUFF_LAYER"] = std::to_string(packed);
        d["PUFF_CANDIDATES"] = std::to_string(kEnvelopeCandidates);
        d["PUFF_DETAIL"] = "1";
        d["PUFF_SHADOW_MAP"] = shadow_map ? "1" : "0";
        if (shadow_map) world.resource<LightEnvironment>().bind();
        const Program& p = rc.shaders.graphics("clouds/puff.vert", "clouds/puff.frag", d);
        p.use();
        p.set("u_view_projection", rc.view.view_projection);
        p.set("u_inverse_view_projection", rc.view.inverse_view_projection);
        p.set("u_viewport", glm::vec2(targets.width, targets.height));
        p.set("u_light_dir", light_dir);
        p.set("u_up_radius", glm::vec4(glm::vec3(gp->block.up), gp->block.camera_radius_m));
        p.set("u_range", glm::vec3(range));
        // The puffs are columns of the cells, whose grid lies along east and north.
        p.set("u_axis_wind", glm::vec3(grid.east));
        p.set("u_axis_across", glm::vec3(grid.north));
        p.set("u_axis_up", grid.axis_up);
        glDrawArraysInstanced(GL_TRIANGLES, 0, mesh ? c.proxy_vertices : 6, count);
        glCullFace(GL_BACK);
        glDisable(GL_CULL_FACE);
        end_far_cloud_draw(rc.view.width, rc.view.height);
      });
}

}  // namespace welkin::clouds
