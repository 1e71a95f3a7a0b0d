#pragma once
// The clouds' GPU side: the per-frame block and layer array every cloud shader reads
// (shaders/clouds/density.glsl), the noise volumes generated once per seed, and the render system.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/clouds/components.h"
#include "welkin/core/error.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/shader.h"
#include "welkin/scene/json_fields.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// std140 mirror of CloudsFrame (vec4 and mat4 only: no hidden padding).
struct FrameBlock {
  glm::vec4 planet{0.0f};         // planet radius m, camera altitude m, camera radius m, layer count
  glm::vec4 up{0.0f};             // planet-centred up at the camera; w: max march distance m
  glm::vec4 shell{0.0f};          // lowest base, highest top (altitude m), empty-space step m, largest occupancy block m
  glm::vec4 shape_origin{0.0f};   // camera in shape periods (fraction); w: 1 / period
  glm::vec4 detail_origin{0.0f};
  glm::vec4 steps{0.0f};          // max steps, min step m, max step m, light steps
  glm::vec4 light{0.0f};          // first light step m, octaves, powder, ground albedo
  glm::vec4 medium{0.0f};         // scattering, absorption, phase model, droplet diameter um
  glm::vec4 phase{0.0f};          // g forward, g backward, forward weight, light marched (0 sun, 1 moon)
  glm::vec4 frame{0.0f};          // frame index, shape detail, march width, march height
  glm::vec4 light_model{0.0f};    // multiple scattering (0 octaves, 1 diffusion), march pixel angle, bands, step growth
  glm::vec4 band_low{0.0f};       // altitude bands holding layers (m, at most kMaxBands)
  glm::vec4 band_high{0.0f};
  // The painted coverage map's frame (welkin/scene/painted_map.h), relative to the planet's centre.
  glm::vec4 map_east{0.0f};    // east at the map's centre; w: planet radius / map side
  glm::vec4 map_north{0.0f};   // w: the largest coverage the map adds
  glm::vec4 map_up{0.0f};      // w: 1 when the scene has a map
  glm::vec4 map_origin{0.0f};  // the camera in (east, north, up) from the planet's centre, m
  glm::vec4 noise_mix{0.0f};       // largest displacement of the detail noise by the curl field m (0: off), weather-system amount
  glm::vec4 weather_system{0.0f};  // the camera in weather-system periods (fraction; the scene's origin at the anchor, drift applied); w: 1 / period
  glm::mat4 inverse_view_projection{1.0f};
};
static_assert(sizeof(FrameBlock) == 368, "FrameBlock must match the std140 CloudsFrame block");

// std430 mirror of CloudLayerGpu.
struct LayerBlock {
  glm::vec4 altitude{0.0f};  // base m, thickness m, base variation m, density per m
  glm::vec4 shape{0.0f};     // coverage, shape amount, detail amount, coverage filter width
  glm::vec4 profile{0.0f};   // exp term, exponent, linear term, constant term
  glm::vec4 weather{0.0f};   // camera in weather periods (fraction); w: 1 / period
  glm::vec4 model{0.0f};     // dome, weather channel, casts shadow, follows the coverage map
  // Hand-over to the mesh clusters (clouds.CloudClusters): the march leaves the layer to them from
  // view distance x to z (m; x = 0: never), cross-fading over y (m).
  glm::vec4 handover{0.0f};
};

// Where the planet is and when it is: what the clouds read of other modules (through reflection).
struct CloudsContext {
  double planet_radius_m = 6360000.0;
  glm::dvec3 planet_center_m{0.0, 0.0, -6360000.0};
  double time_s = 0.0;               // drives the wind: the time of day when there is one
  glm::vec3 sun_direction{0, 0, 1};  // toward the sun
  bool sun_up_for_clouds = true;     // the sun still lights cloud tops (else the moon is marched)
  // The painted coverage map, when the scene has one: the most it adds to a layer's coverage
  // ((largest texel - 128) / 127, below 0 when it only clears) and its revision.
  bool has_coverage_map = false;
  float coverage_map_raise = 0.0f;
  uint64_t coverage_map_revision = 0;
};
// A layer's coverage c where the weather systems' signal is g (uniform on [0, 1]): raised where
// g > 0.5 and lowered where g < 0.5 by up to amount x 4 c (1 - c), so that 0 and 1 stay clear and
// overcast and the planet's mean stays c.
inline double system_coverage(double c, double g, double amount) {
  const double v = c + amount * (2.0 * g - 1.0) * 4.0 * c * (1.0 - c);
  return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}
// What the frame block needs of the generated noise.
struct NoiseFacts {
  glm::vec3 system_anchor{0.5f};  // a texel (uvw) of the systems' volume whose signal is 0.5: the scene's origin sits there
  float weather_step = 0.0f;      // the largest change of that signal between neighbouring texels
};
// Coverage a painted map texel adds (128 nothing, 255 +1, 0 about -1).
inline double painted_coverage_offset(double texel) { return (texel - 128.0) / 127.0; }

inline constexpr int kMaxBands = 4;
// The layers' altitude ranges merged into at most kMaxBands disjoint bands (closest gaps closed first).
std::vector<glm::vec2> altitude_bands(std::vector<glm::vec2> ranges, int max_bands = kMaxBands);

// The layers that can hold cloud this frame (visible, soloed when any is, coverage, thickness and
// density above zero), packed.
struct PackedLayers {
  std::vector<LayerBlock> layers;
  std::vector<glm::vec2> ranges;  // each packed layer's altitude range, its base's variation included
  std::vector<int> source_index;  // the component's layer index of each packed layer
  float lowest_m = 0.0f, highest_m = 0.0f;
  float lowest_shadow_m = 0.0f, highest_shadow_m = 0.0f;
  bool any_shadow = false;
};
PackedLayers pack_layers(const VolumetricClouds& clouds, const CloudsContext& context, const glm::dvec3& camera_m);
FrameBlock make_frame_block(const VolumetricClouds& clouds, const CloudsContext& context, const NoiseFacts& noise,
                            const FrameView& view, const PackedLayers& layers, int march_width, int march_height,
                            uint64_t frame_index);
// The shape model of a genus: dome (0 sheet .. 1 dome) and weather frequency relative to the period.
struct GenusModel {
  float dome;
  float weather_frequency;
};
GenusModel genus_model(Genus genus);

// std140 mirror of the light term's CloudsShadow block (shaders/clouds/light_term.glsl): one plane
// per cascade, nearest first.
inline constexpr int kMaxShadowCascades = 4;
struct ShadowBlock {
  glm::vec4 origin[kMaxShadowCascades]{};  // camera-relative centre; w: 1 while the cascade is valid
  glm::vec4 axis_u[kMaxShadowCascades]{};  // axis per map unit; w: the columns' start toward the sun
  glm::vec4 axis_v[kMaxShadowCascades]{};  // w: side (m)
  glm::vec4 light{0.0f};                   // toward the sun; w: |sun.z|
  glm::vec4 up{0.0f};                      // up at the camera; w: cascade count
};

// What the shadow map was made from; a frame whose key is not stale reuses it.
struct ShadowKey {
  bool wanted = false;
  glm::vec3 sun{0.0f};
  double time_s = 0.0;
  glm::dvec3 anchor_m{0.0};  // the camera when the map was made: the map's centre
  float texel_m = 1.0f, max_wind_mps = 0.0f;
  int size = 0;
  std::vector<float> settings;  // the layers' and medium's values the map depends on
  // Stale when the sun turned by more than ~0.05 degrees, the settings changed, the wind moved the
  // clouds by half a texel, or the camera left the middle half of the map.
  bool stale(const ShadowKey& now) const {
    return glm::dot(sun, now.sun) < 0.9999996f || settings != now.settings || size != now.size ||
           std::abs(now.time_s - time_s) * max_wind_mps > 0.5 * texel_m ||
           glm::length(now.anchor_m - anchor_m) > 0.125 * texel_m * size;
  }
};

// Noise volumes, generated on the GPU once per seed (sizes fixed by the module).
inline constexpr int kShapeNoiseSize = 128, kDetailNoiseSize = 32, kWeatherNoiseSize = 64, kBlueNoiseSize = 64;
inline constexpr int kSystemsNoiseSize = 32;
inline constexpr int kWeatherOccupancySize = 16;  // blocks of 4^3 weather texels

// std430 mirror of ClusterPuff (shaders/clouds/clusters.glsl): one puff, written by the placement
// compute each frame, read by the puffs' draw.
struct ClusterPuffGpu {
  glm::vec4 centre;            // camera-relative m; w: peak extinction 1/m (0: no puff)
  glm::vec4 radii;             // along the clusters' axes (wind, across, up) m; w: optical depth toward the light through the cluster's other puffs
  glm::vec4 light;             // irradiance of the marched light at the centre; w: distance from the camera m
  glm::vec4 sky;               // sky irradiance on a horizontal plane at the centre; w: the centre's height above the cluster's base m
  glm::vec4 ap_inscattering;   // the air between the camera and the centre
  glm::vec4 ap_transmittance;
  glm::vec4 light_gradient;    // how that optical depth changes across the puff: per unit of its normalised axes
};
static_assert(sizeof(ClusterPuffGpu) == 112, "ClusterPuffGpu must match the std430 ClusterPuff struct");

struct CloudsGpu;
// Where the clusters and the billboards stand: a grid of cells in the camera's tangent plane,
// drifting with the layer's wind (shaders/clouds/placement.glsl), of which stages 0 and 1 of
// clusters_place.comp score every cell and choose the nearest that hold cloud.
struct PlacementGrid {
  int grid = 2;                  // cells per side
  double cell_m = 1.0;
  glm::ivec2 first_cell{0};      // the global index of cell (0, 0)
  glm::vec2 first_corner{0.0f};  // its corner, camera-relative (east, north) m
  glm::dvec3 east{1, 0, 0}, north{0, 1, 0};
  glm::vec2 wind_en{1.0f, 0.0f};  // the wind's direction in (east, north)
  glm::vec3 axis_wind{1, 0, 0}, axis_across{0, 1, 0}, axis_up{0, 0, 1};  // camera-relative
};
PlacementGrid placement_grid(const CloudsGpu& gpu, const FrameView& view, const CloudLayer& layer, double cell_m, double far_m);
void set_placement_uniforms(const Program& p, const PlacementGrid& g, uint32_t seed);
// The buffers of the placement's stages 0 and 1, grown when needed.
struct PlacementBuffers {
  std::unique_ptr<Buffer> cells, chosen, cell_order;
  size_t cell_capacity = 0, chosen_capacity = 0;
  int cell_order_grid = -1;  // the grid the cells' order (nearest first) was made for
  void ensure(int grid, int chosen_count);
  // Binds them (2 cells, 3 chosen, 4 order) and runs stages 0 and 1 of clusters_place.comp: of
  // the cells whose centres lie within `ring` (m from the camera), the `choose` nearest that hold cloud.
  void choose(ShaderLibrary& shaders, const ShaderDefines& field, const PlacementGrid& g, int layer, int choose,
              glm::vec2 ring, uint32_t seed) const;
};
void ensure_buffer(std::unique_ptr<Buffer>& buffer, size_t& capacity, size_t bytes);
int next_power_of_two(int n);

// The mesh clusters' GPU state (src/clusters.cpp).
struct ClustersGpu {
  std::unique_ptr<Buffer> proxy;       // the puff's proxy mesh as a triangle list of vec4 (pulled by gl_VertexID)
  int proxy_vertices = 0, proxy_level = -1;
  PlacementBuffers placement;
  std::unique_ptr<Buffer> puffs, order;
  size_t puff_capacity = 0, order_capacity = 0;
  GLuint vao = 0;
  int puff_count = 0;                  // instances drawn last frame (clusters x puffs)
  ~ClustersGpu();
};

// std430 mirror of Billboard (shaders/clouds/billboards.glsl): one billboard, written by the
// placement each frame.
struct BillboardGpu {
  glm::vec4 centre;            // camera-relative m (the archetype box's centre); w: optical-depth scale (0: none)
  glm::vec4 light;             // irradiance of the marched light at the centre; w: distance m
  glm::vec4 sky;               // sky irradiance on a horizontal plane; w: archetype index
  glm::vec4 ap_inscattering;  // w: the archetype's turn about the vertical (radians)
  glm::vec4 ap_transmittance;
};
static_assert(sizeof(BillboardGpu) == 80, "BillboardGpu must match the std430 Billboard struct");

// What an atlas was baked from: a frame whose key equals it reuses the atlas.
struct BillboardBakeKey {
  std::vector<float> values;
  bool operator==(const BillboardBakeKey&) const = default;
};

// The billboards' GPU state (src/billboards.cpp).
struct BillboardsGpu {
  std::unique_ptr<Texture> volume, atlas;  // the archetypes' extinction, and their views
  std::unique_ptr<Buffer> archetypes;      // each archetype's place in the noise and its weather's score
  PlacementBuffers placement;
  std::unique_ptr<Buffer> billboards, order;
  size_t billboard_capacity = 0, order_capacity = 0;
  BillboardBakeKey baked;  // what the atlas holds (empty: nothing yet)
  int bakes = 0;           // how often it was baked (tests, stats)
  GLuint vao = 0;
  int drawn = 0;           // instance slots drawn last frame
  ~BillboardsGpu();
};

struct CloudsGpu {
  static constexpr std::string_view kTypeName = "clouds.Gpu";
  // shape: RGBA8, r the Perlin-Worley shape, gba the curl field c as 0.5 + 0.5 c (longest vector 1),
  // read in the same fetch as the shape it displaces the detail noise from.
  std::unique_ptr<Texture> shape, detail, weather, blue_noise, shadow_map;
  std::unique_ptr<Texture> systems;  // the weather systems' signal (R8, smooth, equalised)
  std::unique_ptr<Texture> weather_maximum;  // the coarse occupancy for empty-space skipping
  // The painted coverage map as uploaded (1 x 1 neutral when the scene has none), and what it holds.
  std::unique_ptr<Texture> coverage_map;
  std::string coverage_map_file;
  uint64_t coverage_map_revision = 0;
  float coverage_map_raise = 0.0f;
  int noise_seed = -1;   // the seed the noise was made from (-1: none yet)
  NoiseFacts noise_facts;
  int noise_builds = 0;       // how often the noise was generated (tests, stats)
  int noise_cache_reads = 0;  // how often it was read from the disk cache instead
  std::unique_ptr<Buffer> frame_buffer, layer_buffer, shadow_buffer;
  size_t layer_capacity = 0;
  ShadowBlock shadow;    // as last uploaded (valid: origin[k].w = 1)
  ShadowKey shadow_keys[kMaxShadowCascades];     // what each cascade holds
  bool shadow_rebuild[kMaxShadowCascades] = {};  // this frame remakes it
  int shadow_builds = 0;                         // cascades made
  FrameBlock block;      // this frame's, uploaded before the geometry
  std::vector<LayerBlock> layers;  // and its packed layers (the CPU reference reads them)
  // Temporal upscaling: the last two results at the march resolution. The one a frame writes is made
  // at its size; the last frame's may be of another (the resolve reads it by its own size), so a
  // frame whose size changed (a view that starts or stops moving, Camera::moving_render_scale) still
  // marches one pixel of each block.
  std::unique_ptr<Texture> history_color[2];
  int history_index = 0;      // the one the next frame writes
  bool history_valid = false;  // history_color[1 - history_index] holds the last frame
  size_t full_marches = 0;     // frames that marched every pixel (no history to reproject; tests)
  glm::mat4 previous_view_projection{1.0f};
  glm::dvec3 previous_camera_m{0.0};
  uint64_t temporal_frame = 0;
  // A still view keeps its clouds: the digest of everything the march and the resolve read
  // (clouds_system), and how many frames in a row marched under it. After a whole cycle of the
  // upscaling's blocks every pixel of the history was marched under it, and the frames after
  // composite the history as it is instead of marching again.
  uint64_t march_state = 0;
  int march_state_frames = 0;
  int marches = 0;  // frames that marched (tests, stats)
  bool has_layers = false;  // some layer can hold cloud this frame
  CloudsContext context;    // this frame's
  int clusters_layer = -1;  // the packed layer the mesh clusters draw (-1: none)
  float clusters_near_m = 0.0f;  // where the march hands it over this frame (clouds.CloudLod moves it)
  float lod_near_m = -1.0f;      // the budget's hand-over, carried between frames (-1: not started)
  ClustersGpu clusters;
  int billboards_layer = -1;  // the packed layer the billboards draw (-1: none)
  glm::vec4 billboards_fade{0.0f};  // their cross-fades this frame: in from x to y, out from z to w (m)
  BillboardsGpu billboards;
};

// Values set in code or by sequences never passed the loaders' checks: one is checked here, and a
// bad one is an error naming the component and field, not a black or hanging frame.
template <class T>
void check_component(const T& component) {
  try {
    check_object(type_desc<T>(), &component);
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(T::kTypeName));
  }
}

// Declares the cloud shadows and sky occlusion as a term of the world's light environment.
void add_light_term(World& world);
// Render phase, before the geometry (order -50): noise when the seed changed, this frame's block and
// layers, and the shadow map every material reads.
void shadow_system(SystemContext& sc);
// Render phase, after the atmosphere's aerial perspective (order 150): the march at the quality's
// resolution and the composite over the frame.
void clouds_system(SystemContext& sc);
// Render phase, after the god rays and before the march (order 145): the mesh clusters, placed from
// the field, lit, sorted and drawn over the frame; the march then stops where they turn opaque.
void clusters_system(SystemContext& sc);
// Render phase, before the mesh clusters (order 144): the billboards, baked when their key changed,
// placed, lit, sorted and drawn into the mid- and far-range clouds' targets.
void billboards_system(SystemContext& sc);
// The targets the mid- and far-range clouds (billboards, then clusters) draw into at a fraction of
// the frame's size, published on the graph's blackboard for the march: premultiplied colour and
// where they turn opaque. The first path to draw in a frame creates them (cleared), the next draws
// over them. Call from a pass's setup.
struct FarCloudTargets {
  ResourceHandle color, front;
  int width = 0, height = 0;
  bool created = false;  // this pass must clear them
};
FarCloudTargets far_cloud_targets(RenderGraph& graph, PassBuilder& b, int width, int height);
// Clears new targets, binds them (the framebuffer returned, kept while drawing) with the blending
// both paths use, and the viewport; restored by end_far_cloud_draw.
Framebuffer begin_far_cloud_draw(PassContext& pc, const FarCloudTargets& t);
void end_far_cloud_draw(int frame_width, int frame_height);
// Sorts a (key, index) buffer at binding 5 by key, far first (a power-of-two size).
void sort_far_to_near(ShaderLibrary& shaders, int size);
// The proxy mesh of one puff: a cube refined by Catmull-Clark (OpenSubdiv) onto the unit sphere and
// pushed out until it encloses it, as a triangle list (counter-clockwise from outside).
std::vector<glm::vec4> puff_proxy_mesh(int level);
// Binds the density field's block, layers and noise (shaders/clouds/density.glsl's bindings).
void bind_field(const CloudsGpu& gpu);
// The field's compile-time description for a shader that includes density.glsl.
ShaderDefines field_defines(const CloudsGpu& gpu);
// The light model's choices (multiple scattering, powder, phase function) for a shader that includes
// clouds/light_model.glsl: compiled in, since llvmpipe evaluates both sides of a uniform branch.
ShaderDefines light_model_defines(const CloudsGpu& gpu);
// Noise generation alone (also used by the CPU reference's field, which reads the volumes back).
void ensure_noise(World& world, int seed);

}  // namespace welkin::clouds
