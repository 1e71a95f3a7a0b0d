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
#include "welkin/clouds/gpu.h"
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
  for (int i = 0; i < 8; ++i) cube.positions.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
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

const CloudClusters* first_clusters(World& world) {
  Registry& reg = world.registry();
  const Entity e = reg.first<CloudClusters>();
  return e.is_null() ? nullptr : reg.get<CloudClusters>(e);
}

// The shape a genus's clusters take: dome (as the field's), form (0 heaps, 1 sheets, 2 streaks).
glm::vec2 genus_form(Genus genus) {
  switch (genus) {
    case Genus::stratus:
    case Genus::altostratus:
    case Genus::nimbostratus:
    case Genus::cirrostratus: return {genus_model(genus).dome, 1.0f};
    case Genus::cirrus: return {genus_model(genus).dome, 2.0f};
    default: return {genus_model(genus).dome, 0.0f};
  }
}

void ensure_buffer(std::unique_ptr<Buffer>& buffer, size_t& capacity, size_t bytes) {
  bytes = std::max<size_t>(bytes, 16);
  if (!buffer || capacity < bytes) {
    buffer = std::make_unique<Buffer>(bytes);
    capacity = bytes;
  }
}

int next_power_of_two(int n) {
  int m = 1;
  while (m < n) m *= 2;
  return m;
}

// Cells of a grid x grid square nearest its middle first (the camera lies in cell (grid/2, grid/2)).
std::vector<int32_t> cells_nearest_first(int grid) {
  std::vector<int32_t> cells(size_t(grid) * size_t(grid));
  for (size_t i = 0; i < cells.size(); ++i) cells[i] = int32_t(i);
  const double middle = 0.5 * grid;
  auto distance2 = [&](int32_t c) {
    const double x = c % grid + 0.5 - middle, y = c / grid + 0.5 - middle;
    return x * x + y * y;
  };
  std::stable_sort(cells.begin(), cells.end(), [&](int32_t a, int32_t b) { return distance2(a) < distance2(b); });
  return cells;
}

}  // namespace

void clusters_system(SystemContext& sc) {
  World& world = sc.world;
  auto& gpu = world.resource<CloudsGpu>();
  ClustersGpu& cg = gpu.clusters;
  const CloudClusters* clusters = first_clusters(world);
  if (!clusters) return;
  check_component(*clusters);
  Registry& reg = world.registry();
  const Entity ce = reg.first<VolumetricClouds>();
  if (ce.is_null())
    throw Error(ErrorInfo{.path = std::string(CloudClusters::kTypeName),
                          .expected = "a clouds.VolumetricClouds in the scene (the layers the clusters draw)",
                          .found = "none"});
  const VolumetricClouds& clouds = *reg.get<VolumetricClouds>(ce);
  if (clusters->layer >= int(clouds.layers.size()))
    throw Error(ErrorInfo{.path = std::string(CloudClusters::kTypeName) + "/layer",
                          .expected = "the index of a layer of clouds.VolumetricClouds (0 to " + std::to_string(int(clouds.layers.size()) - 1) + ")",
                          .found = std::to_string(clusters->layer)});
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
  const int grid = std::max(2, 2 * int(std::ceil(double(clusters->far_m) / clusters->cell_m)));
  if (cg.cell_order_grid != grid) {
    cg.cell_order = cells_nearest_first(grid);
    cg.cell_order_grid = grid;
    cg.cell_order_buffer = std::make_unique<Buffer>(cg.cell_order.size() * sizeof(int32_t), cg.cell_order.data());
  }
  const int order_size = next_power_of_two(count);
  ensure_buffer(cg.cells, cg.cell_capacity, size_t(grid) * size_t(grid) * sizeof(float));
  ensure_buffer(cg.chosen, cg.chosen_capacity, size_t(clusters->clusters) * sizeof(int32_t));
  ensure_buffer(cg.puffs, cg.puff_capacity, size_t(count) * sizeof(ClusterPuffGpu));
  ensure_buffer(cg.order, cg.order_capacity, size_t(order_size) * 2 * sizeof(uint32_t));
  const int width = std::max(1, int(std::ceil(view.width * clusters->resolution_scale)));
  const int height = std::max(1, int(std::ceil(view.height * clusters->resolution_scale)));

  // The camera's tangent plane, the wind's direction in it, and the drifting grid's cell under the camera.
  const CloudsContext& ctx = gpu.context;
  const glm::dvec3 up = glm::dvec3(gpu.block.up);
  // East: the world's x axis in the camera's tangent plane (its y where up is nearly x, seen from orbit).
  const glm::dvec3 x_axis = std::abs(up.x) < 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 east = glm::normalize(x_axis - up * glm::dot(up, x_axis));
  const glm::dvec3 north = glm::cross(up, east);
  const CloudLayer& layer = clouds.layers[size_t(clusters->layer)];
  const glm::dvec2 wind = glm::dvec2(layer.wind_mps);
  const glm::dvec2 drift = wind * ctx.time_s;
  const glm::dvec2 camera_en{glm::dot(view.camera_position_m, east), glm::dot(view.camera_position_m, north)};
  const double cell = clusters->cell_m;
  const glm::dvec2 in_grid = (camera_en - drift) / cell;
  const glm::dvec2 camera_cell = glm::floor(in_grid);
  const glm::ivec2 first_cell = glm::ivec2(camera_cell) - glm::ivec2(grid / 2);
  const glm::vec2 first_corner = glm::vec2((glm::dvec2(first_cell) - in_grid) * cell);
  const glm::vec2 wind_en = glm::length(wind) > 1e-6 ? glm::vec2(glm::normalize(wind)) : glm::vec2(1.0f, 0.0f);
  const glm::vec3 axis_wind = glm::vec3(east) * wind_en.x + glm::vec3(north) * wind_en.y;
  const glm::vec3 axis_up = glm::vec3(up);
  const glm::vec3 axis_across = glm::cross(axis_up, axis_wind);
  const bool moon = gpu.block.phase.w > 0.5f;
  const glm::vec3 light_dir = moon ? glm::vec3(0, 0, 1) : ctx.sun_direction;
  const glm::vec2 form = genus_form(layer.genus);
  const ShaderDefines field = field_defines(gpu);
  const glm::vec4 range{gpu.clusters_near_m, clusters->crossfade_m, clusters->far_m, clusters->puff_size};
  const glm::vec4 genus{form.x, form.y, clusters->density_scale, 0.0f};
  const int n_clusters = clusters->clusters, n_puffs = clusters->puffs_per_cluster;
  const bool sorted = clusters->compositing == ClusterCompositing::sorted;
  CloudsGpu* gp = &gpu;
  cg.puff_count = count;

  RenderGraph& g = *sc.graph;
  g.add_pass(
      "clouds.clusters_place", [](PassBuilder& b) { b.side_effect(); },
      [gp, &rc, &world, field, grid, first_cell, first_corner, east, north, wind_en, packed, n_clusters, n_puffs,
       order_size, range, genus, light_dir, moon, axis_wind, axis_across, axis_up, sorted,
       seed = uint32_t(clusters->seed), count, cell](PassContext&) {
        ClustersGpu& c = gp->clusters;
        bind_field(*gp);
        world.resource<LightEnvironment>().bind();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, c.puffs->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, c.cells->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, c.chosen->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, c.cell_order_buffer->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, c.order->id());
        const int invocations[4] = {grid * grid, 1, count, order_size};
        for (int stage = 0; stage < 4; ++stage) {
          ShaderDefines d = field;
          d["CLUSTERS_STAGE"] = std::to_string(stage);
          const Program& p = rc.shaders.compute("clouds/clusters_place.comp", d);
          p.set("u_grid", grid);
          p.set("u_cell_m", float(cell));
          glProgramUniform2i(p.id(), p.location("u_first_cell"), first_cell.x, first_cell.y);
          p.set("u_first_corner", first_corner);
          p.set("u_east", glm::vec3(east));
          p.set("u_north", glm::vec3(north));
          p.set("u_wind_en", wind_en);
          p.set("u_layer", packed);
          p.set("u_clusters", n_clusters);
          p.set("u_puffs", n_puffs);
          glProgramUniform1ui(p.id(), p.location("u_seed"), seed);
          p.set("u_range", range);
          p.set("u_genus", genus);
          p.set("u_order_size", order_size);
          p.set("u_light_dir", light_dir);
          p.set("u_light", moon ? 1 : 0);
          p.set("u_axis_wind", axis_wind);
          p.set("u_axis_across", axis_across);
          p.set("u_axis_up", axis_up);
          dispatch_compute(p, group_count(invocations[stage], 64), 1);
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        if (!sorted) return;
        // Far first: blocks of 1024 in shared memory, then each larger merge's wide steps across
        // the buffer and its narrow ones in shared memory again.
        auto sort_pass = [&](int mode, int k, int j, int groups) {
          const Program& p = rc.shaders.compute("clouds/clusters_sort.comp", {{"CLUSTERS_SORT_MODE", std::to_string(mode)}});
          p.set("u_size", order_size);
          p.set("u_k", k);
          p.set("u_j", j);
          dispatch_compute(p, groups, 1);
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        };
        const int blocks = std::max(order_size / 1024, 1);
        sort_pass(0, 0, 0, blocks);
        for (int k = 2048; k <= order_size; k *= 2) {
          for (int j = k / 2; j >= 1024; j /= 2) sort_pass(2, k, j, group_count(order_size / 2, 512));
          sort_pass(1, k, 0, blocks);
        }
      });

  const FrameTargets t = *sc.targets;
  const int samples = clusters->samples;
  auto color = std::make_shared<ResourceHandle>(), front = std::make_shared<ResourceHandle>();
  g.add_pass(
      "clouds.clusters_draw",
      [&](PassBuilder& b) {
        b.read(t.depth);
        *color = b.create("clouds.clusters", TextureDesc{.width = width, .height = height, .format = TextureFormat::rgba16f});
        *front = b.create("clouds.cluster_front",
                          TextureDesc{.width = width, .height = height, .format = TextureFormat::r32f, .linear_filter = false});
      },
      [gp, &rc, t, front, color, count, axis_wind, axis_across, axis_up, light_dir, samples, mesh, width,
       height](PassContext& pc) {
        ClustersGpu& c = gp->clusters;
        Framebuffer fb({&pc.texture(*color), &pc.texture(*front)}, nullptr);
        fb.bind();
        glViewport(0, 0, width, height);
        const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far_away = 3.4e38f;
        glClearTexImage(pc.texture(*color).id(), 0, GL_RGBA, GL_FLOAT, nothing);
        glClearTexImage(pc.texture(*front).id(), 0, GL_RED, GL_FLOAT, &far_away);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        // Premultiplied: puff + (1 - opacity) x behind; the front by minimum. (Set for every buffer
        // first: the atmosphere's pass leaves a second-source blend, which GL forbids with two.)
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glBlendFunci(1, GL_ONE, GL_ONE);
        glBlendEquationi(1, GL_MIN);
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
        const Program& p = rc.shaders.graphics("clouds/puff.vert", "clouds/puff.frag", {{"PUFF_PROXY_MESH", mesh ? "1" : "0"}});
        p.use();
        p.set("u_view_projection", rc.view.view_projection);
        p.set("u_inverse_view_projection", rc.view.inverse_view_projection);
        p.set("u_viewport", glm::vec2(width, height));
        p.set("u_light_dir", light_dir);
        p.set("u_samples", samples);
        p.set("u_up_radius", glm::vec4(glm::vec3(gp->block.up), gp->block.planet.z));
        p.set("u_axis_wind", axis_wind);
        p.set("u_axis_across", axis_across);
        p.set("u_axis_up", axis_up);
        glDrawArraysInstanced(GL_TRIANGLES, 0, mesh ? c.proxy_vertices : 6, count);
        glCullFace(GL_BACK);
        glDisable(GL_CULL_FACE);
        glBlendEquationi(1, GL_FUNC_ADD);
        glDisable(GL_BLEND);
        glViewport(0, 0, rc.view.width, rc.view.height);
      });
  // Published for the march (which stops at the front) and its composite (which lays the puffs
  // over the frame, under the nearer volumetric clouds).
  g.blackboard["clouds.clusters"] = *color;
  g.blackboard["clouds.cluster_front"] = *front;
}

}  // namespace welkin::clouds
