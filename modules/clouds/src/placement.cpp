// What the mid- and far-range paths (mesh clusters, billboards) share: the drifting grid of cells
// they stand on and its scoring and choosing stages, the far-to-near sort, and the targets both
// draw into before the march composites them.
#include <algorithm>
#include <bit>
#include <cmath>

#include "clouds_gpu.h"
#include "placement.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"

namespace welkin::clouds {

void ensure_buffer(std::unique_ptr<Buffer>& buffer, size_t& capacity, size_t bytes) {
  bytes = std::max<size_t>(bytes, 16);
  if (!buffer || capacity < bytes) {
    buffer = std::make_unique<Buffer>(bytes);
    capacity = bytes;
  }
}

const VolumetricClouds& drawn_clouds(Registry& reg, std::string_view component, int layer,
                                     std::string_view drawer) {
  const Entity ce = reg.first<VolumetricClouds>();
  if (ce.is_null())
    throw Error(ErrorInfo{.path = std::string(component),
                          .expected = "a clouds.VolumetricClouds in the scene (the layers the " +
                                      std::string(drawer) + " draw)",
                          .found = "none"});
  const VolumetricClouds& clouds = *reg.get<VolumetricClouds>(ce);
  if (layer >= int(clouds.layers.size()))
    throw Error(ErrorInfo{.path = std::string(component) + "/layer",
                          .expected = "the index of a layer of clouds.VolumetricClouds (0 to " +
                                      std::to_string(int(clouds.layers.size()) - 1) + ")",
                          .found = std::to_string(layer)});
  return clouds;
}

int next_power_of_two(int n) {
  int m = 1;
  while (m < n) m *= 2;
  return m;
}

namespace {

// Cells of a grid x grid square nearest its middle first (the camera lies in cell (grid/2, grid/2)).
std::vector<int32_t> cells_nearest_first(int grid) {
  std::vector<int32_t> cells(size_t(grid) * size_t(grid));
  for (size_t i = 0; i < cells.size(); ++i) cells[i] = int32_t(i);
  const double middle = 0.5 * grid;
  auto distance2 = [&](int32_t c) {
    const double x = c % grid + 0.5 - middle, y = c / grid + 0.5 - middle;
    return x * x + y * y;
  };
  std::stable_sort(cells.begin(), cells.end(),
                   [&](int32_t a, int32_t b) { return distance2(a) < distance2(b); });
  return cells;
}

}  // namespace

PlacementGrid placement_grid(const CloudsGpu& gpu, const FrameView& view, const CloudLayer& layer,
                             double cell_m, double far_m) {
  PlacementGrid g;
  g.grid = std::max(2, 2 * int(std::ceil(far_m / cell_m)));
  g.cell_m = cell_m;
  const glm::dvec3 up = glm::dvec3(gpu.block.up);
  // East: the world's x axis in the camera's tangent plane (its y where up is nearly x, seen from orbit).
  const glm::dvec3 x_axis = std::abs(up.x) < 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  g.east = glm::normalize(x_axis - up * glm::dot(up, x_axis));
  g.north = glm::cross(up, g.east);
  const glm::dvec2 wind = glm::dvec2(layer.wind_mps);
  const glm::dvec2 drift = wind * gpu.context.time_s;
  const glm::dvec2 camera_en{glm::dot(view.camera_position_m, g.east),
                             glm::dot(view.camera_position_m, g.north)};
  const glm::dvec2 in_grid = (camera_en - drift) / cell_m;
  const glm::dvec2 camera_cell = glm::floor(in_grid);
  g.first_cell = glm::ivec2(camera_cell) - glm::ivec2(g.grid / 2);
  g.first_corner = glm::vec2((glm::dvec2(g.first_cell) - in_grid) * cell_m);
  g.wind_en = glm::length(wind) > 1e-6 ? glm::vec2(glm::normalize(wind)) : glm::vec2(1.0f, 0.0f);
  g.axis_wind = glm::vec3(g.east) * g.wind_en.x + glm::vec3(g.north) * g.wind_en.y;
  g.axis_up = glm::vec3(up);
  g.axis_across = glm::cross(g.axis_up, g.axis_wind);
  return g;
}

void set_placement_uniforms(const Program& p, const PlacementGrid& g, uint32_t seed) {
  p.set("u_grid", g.grid);
  p.set("u_cell_m", float(g.cell_m));
  glProgramUniform2i(p.id(), p.location("u_first_cell"), g.first_cell.x, g.first_cell.y);
  p.set("u_first_corner", g.first_corner);
  p.set("u_east", glm::vec3(g.east));
  p.set("u_north", glm::vec3(g.north));
  glProgramUniform1ui(p.id(), p.location("u_seed"), seed);
}

void PlacementBuffers::ensure(int grid, int chosen_count) {
  if (cell_order_grid != grid) {
    const std::vector<int32_t> order = cells_nearest_first(grid);
    cell_order = std::make_unique<Buffer>(order.size() * sizeof(int32_t), order.data());
    cell_order_grid = grid;
  }
  ensure_buffer(cells, cell_capacity, size_t(grid) * size_t(grid) * sizeof(float));
  ensure_buffer(chosen, chosen_capacity, size_t(std::max(chosen_count, 1)) * sizeof(int32_t));
}

void PlacementBuffers::choose(ShaderLibrary& shaders, const ShaderDefines& field, const PlacementGrid& g,
                              int layer, int choose_count, glm::vec2 ring, uint32_t seed,
                              bool in_view) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, cells->id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, chosen->id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, cell_order->id());
  const int invocations[2] = {g.grid * g.grid, 1};
  for (int stage = 0; stage < 2; ++stage) {
    ShaderDefines d = field;
    d["CLUSTERS_STAGE"] = std::to_string(stage);
    const Program& p = shaders.compute("clouds/clusters_place.comp", d);
    set_placement_uniforms(p, g, seed);
    p.set("u_layer", layer);
    p.set("u_clusters", choose_count);
    p.set("u_ring", ring);
    p.set("u_in_view", in_view ? 1 : 0);
    dispatch_compute(p, group_count(invocations[stage], 64), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

void sort_far_to_near(ShaderLibrary& shaders, int size) {
  // Blocks of up to 1024 in shared memory, then each larger merge's wide steps across the buffer and
  // its narrow ones in shared memory again. The shared-memory steps are compiled in as a list.
  if (size < 2) return;
  const int block = std::min(size, 1024), block_bits = std::countr_zero(unsigned(block));
  // Pairs per invocation in the shared-memory steps (clusters_sort.comp): 2^bits of them.
  const int bits = std::min(4, block_bits);
  // The steps (k, bit of j) in order, grouped in rounds whose bits fall in one window.
  auto rounds = [&](bool whole_sort) {
    std::vector<std::pair<std::string, int>> steps;
    if (whole_sort) {
      for (int k = 2; k <= block; k *= 2)
        for (int g = std::countr_zero(unsigned(k)) - 1; g >= 0; --g) steps.emplace_back(std::to_string(k), g);
    } else {
      for (int g = block_bits - 1; g >= 0; --g)
        steps.emplace_back("u_k", g);  // a larger merge's narrow steps
    }
    std::string list;
    int low = -1;
    for (const auto& [k, g] : steps) {
      const int window = std::min(g / bits * bits, block_bits - bits);
      if (window != low) {
        if (low >= 0) list += "SORT_ROUND_END(" + std::to_string(low) + ") ";
        low = window;
        list += "SORT_ROUND_BEGIN(" + std::to_string(low) + ") ";
      }
      list += "SORT_STEP(" + k + ", " + std::to_string(low) + ", " + std::to_string(g - low) + ") ";
    }
    return list + "SORT_ROUND_END(" + std::to_string(low) + ")";
  };
  auto sort_pass = [&](int mode, int k, int j, int groups) {
    ShaderDefines d = {{"CLUSTERS_SORT_MODE", std::to_string(mode)}};
    if (mode != 2) {
      d["CLUSTERS_SORT_BLOCK"] = std::to_string(block);
      d["CLUSTERS_SORT_BITS"] = std::to_string(bits);
      d["CLUSTERS_SORT_PER"] = std::to_string(1 << bits);
      d["CLUSTERS_SORT_ROUNDS"] = rounds(mode == 0);
    }
    const Program& p = shaders.compute("clouds/clusters_sort.comp", d);
    p.set("u_size", size);
    p.set("u_k", k);
    p.set("u_j", j);
    dispatch_compute(p, groups, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  const int blocks = size / block;
  sort_pass(0, 0, 0, blocks);
  for (int k = 2 * block; k <= size; k *= 2) {
    for (int j = k / 2; j >= block; j /= 2) sort_pass(2, k, j, group_count(size / 2, 512));
    sort_pass(1, k, 0, blocks);
  }
}

FarCloudTargets far_cloud_targets(RenderGraph& graph, int width, int height) {
  FarCloudTargets t{.color = graph.published(kFarCloudsColor), .front = graph.published(kFarCloudsFront)};
  if (t.color.valid() && t.front.valid()) {
    t.width = graph.resource_desc(t.color).width;
    t.height = graph.resource_desc(t.color).height;
    return t;
  }
  t.color = graph.create(std::string(kFarCloudsColor.name),
                         TextureDesc{.width = width, .height = height, .format = TextureFormat::rgba16f});
  t.front = graph.create(
      std::string(kFarCloudsFront.name),
      TextureDesc{.width = width, .height = height, .format = TextureFormat::r32f, .linear_filter = false});
  t.width = width, t.height = height, t.created = true;
  graph.publish(kFarCloudsColor, t.color);
  graph.publish(kFarCloudsFront, t.front);
  return t;
}

void write_far_cloud_targets(PassBuilder& b, const FarCloudTargets& t) {
  b.write(t.color);
  b.write(t.front);
}

Framebuffer begin_far_cloud_draw(PassContext& pc, const FarCloudTargets& t) {
  Framebuffer fb({&pc.texture(t.color), &pc.texture(t.front)}, nullptr);
  fb.bind();
  glViewport(0, 0, t.width, t.height);
  if (t.created) {
    const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far_away = 3.4e38f;
    glClearTexImage(pc.texture(t.color).id(), 0, GL_RGBA, GL_FLOAT, nothing);
    glClearTexImage(pc.texture(t.front).id(), 0, GL_RED, GL_FLOAT, &far_away);
  }
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  // Premultiplied: cloud + (1 - opacity) x behind; the front by minimum. (Set for every buffer
  // first: the atmosphere's pass leaves a second-source blend, which GL forbids with two.)
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glBlendFunci(1, GL_ONE, GL_ONE);
  glBlendEquationi(1, GL_MIN);
  return fb;
}

void end_far_cloud_draw(int frame_width, int frame_height) {
  glBlendEquationi(1, GL_FUNC_ADD);
  glDisable(GL_BLEND);
  glViewport(0, 0, frame_width, frame_height);
}

}  // namespace welkin::clouds
