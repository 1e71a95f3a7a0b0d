#pragma once
// Where the mesh clusters and the billboards stand, and the targets both draw into (placement.cpp).
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string_view>

#include "welkin/clouds/components.h"
#include "welkin/core/registry.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/shader.h"

namespace welkin::clouds {

struct CloudsGpu;
// The clouds whose layer `layer` a mid- or far-range path draws (`component`: its component's type
// name, `drawer`: what it draws); an error naming the component when the scene has none or no such
// layer.
const VolumetricClouds& drawn_clouds(Registry& reg, std::string_view component, int layer,
                                     std::string_view drawer);
// Where the clusters and the billboards stand: a grid of cells in the camera's tangent plane,
// drifting with the layer's wind (shaders/clouds/placement.glsl), of which stages 0 and 1 of
// clusters_place.comp score every cell and choose the nearest that hold cloud.
struct PlacementGrid {
  int grid = 2;  // cells per side
  double cell_m = 1.0;
  glm::ivec2 first_cell{0};      // the global index of cell (0, 0)
  glm::vec2 first_corner{0.0f};  // its corner, camera-relative (east, north) m
  glm::dvec3 east{1, 0, 0}, north{0, 1, 0};
  glm::vec2 wind_en{1.0f, 0.0f};  // the wind's direction in (east, north)
  glm::vec3 axis_wind{1, 0, 0}, axis_across{0, 1, 0}, axis_up{0, 0, 1};  // camera-relative
};
PlacementGrid placement_grid(const CloudsGpu& gpu, const FrameView& view, const CloudLayer& layer,
                             double cell_m, double far_m);
void set_placement_uniforms(const Program& p, const PlacementGrid& g, uint32_t seed);
// The buffers of the placement's stages 0 and 1, grown when needed.
struct PlacementBuffers {
  std::unique_ptr<Buffer> cells, chosen, cell_order;
  size_t cell_capacity = 0, chosen_capacity = 0;
  int cell_order_grid = -1;  // the grid the cells' order (nearest first) was made for
  void ensure(int grid, int chosen_count);
  // Binds them (2 cells, 3 chosen, 4 order) and runs stages 0 and 1 of clusters_place.comp: of
  // the cells whose centres lie within `ring` (m from the camera), the `choose` nearest that hold cloud
  // (`in_view`: only cells whose column reaches into the view).
  void choose(ShaderLibrary& shaders, const ShaderDefines& field, const PlacementGrid& g, int layer,
              int choose, glm::vec2 ring, uint32_t seed, bool in_view = false) const;
};
void ensure_buffer(std::unique_ptr<Buffer>& buffer, size_t& capacity, size_t bytes);
int next_power_of_two(int n);
// The targets the mid- and far-range clouds (billboards, then clusters) draw into at a fraction of
// the frame's size, published on the graph for the march: premultiplied colour and where they turn
// opaque. The first path to draw in a frame creates them (its pass clears them), the next draws over
// them. Call before adding the pass that draws them; its setup writes them (write_far_cloud_targets).
inline constexpr GraphKey kFarCloudsColor{"clouds.clusters"};
inline constexpr GraphKey kFarCloudsFront{"clouds.cluster_front"};
struct FarCloudTargets {
  ResourceHandle color, front;
  int width = 0, height = 0;
  bool created = false;  // this pass must clear them
};
FarCloudTargets far_cloud_targets(RenderGraph& graph, int width, int height);
void write_far_cloud_targets(PassBuilder& b, const FarCloudTargets& t);
// Clears new targets, binds them (the framebuffer returned, kept while drawing) with the blending
// both paths use, and the viewport; restored by end_far_cloud_draw.
Framebuffer begin_far_cloud_draw(PassContext& pc, const FarCloudTargets& t);
void end_far_cloud_draw(int frame_width, int frame_height);
// Sorts a (key, index) buffer at binding 5 by key, far first (a power-of-two size).
void sort_far_to_near(ShaderLibrary& shaders, int size);

}  // namespace welkin::clouds
