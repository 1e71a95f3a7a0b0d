#pragma once
#include <map>
#include <string>
// The clouds' GPU state, private to the module: one world resource (CloudsGpu) holding the noise,
// this frame's block and layers, the shadow cascades, the temporal history and the mid- and far-range
// paths' state.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "billboards.h"
#include "clusters.h"
#include "first_hit_skip.h"
#include "frame_block.h"
#include "noise_volumes.h"
#include "shadow_cascades.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/scene/json_fields.h"

namespace welkin::clouds {

struct CloudsGpu {
  static constexpr std::string_view kTypeName = "clouds.Gpu";
  // shape: RGBA8, r the Perlin-Worley shape, gba the curl field c as 0.5 + 0.5 c (longest vector 1),
  // read in the same fetch as the shape it displaces the detail noise from.
  std::unique_ptr<Texture> shape, detail, weather, blue_noise, shadow_map;
  std::unique_ptr<Texture> systems;          // the weather systems' signal (R8, smooth, equalised)
  std::unique_ptr<Texture> weather_maximum;  // the coarse occupancy for empty-space skipping
  // The painted coverage map as uploaded (1 x 1 neutral when the scene has none), and what it holds.
  std::unique_ptr<Texture> coverage_map;
  std::string coverage_map_file;
  uint64_t coverage_map_revision = 0;
  float coverage_map_raise = 0.0f;
  int noise_seed = -1;  // the seed the noise was made from (-1: none yet)
  // The multiple-scattering coefficients as defines (light_model_fit.glsl's names), set only while
  // `welkin accuracy clouds --fit` searches; empty, the committed fit is compiled in.
  std::map<std::string, std::string> light_model_fit;
  NoiseFacts noise_facts;
  int noise_builds = 0;       // how often the noise was generated (tests, stats)
  int noise_cache_reads = 0;  // how often it was read from the disk cache instead
  std::unique_ptr<Buffer> frame_buffer, layer_buffer, shadow_buffer;
  size_t layer_capacity = 0;
  ShadowBlock shadow{};                          // as last uploaded
  ShadowKey shadow_keys[kMaxShadowCascades];     // what each cascade holds
  bool shadow_rebuild[kMaxShadowCascades] = {};  // this frame remakes it
  int shadow_builds = 0;                         // cascades made
  glm::vec2 shadow_altitudes_m{0.0f};            // the lowest and highest altitude of a layer that casts one
  FrameBlock block;                              // this frame's, uploaded before the geometry
  std::vector<LayerBlock> layers;                // and its packed layers (the CPU reference reads them)
  // Temporal upscaling: the last two results at the march resolution. The one a frame writes is made
  // at its size; the last frame's may be of another (the resolve reads it by its own size), so a
  // frame whose size changed (a view that starts or stops moving, Camera::moving_render_scale) still
  // marches one pixel of each block.
  std::unique_ptr<Texture> history_color[2];
  int history_index = 0;       // the one the next frame writes
  bool history_valid = false;  // history_color[1 - history_index] holds the last frame
  size_t full_marches = 0;     // frames that marched every pixel (no history to reproject; tests)
  glm::mat4 previous_view_projection{1.0f};
  glm::dvec3 previous_camera_m{0.0};
  uint64_t temporal_frame = 0;
  // The pixels next to the last frame's silhouettes, listed for their march (silhouette_march.h).
  std::unique_ptr<Buffer> silhouette_list;
  size_t silhouette_list_capacity = 0;
  FirstHitHistory first_hit;  // where the last frame's rays met no cloud (first_hit_skip.h)
  // A still view keeps its clouds: the digest of everything the march and the resolve read
  // (clouds_system), and how many frames in a row marched under it. After a whole cycle of the
  // upscaling's blocks every pixel of the history was marched under it, and the frames after
  // composite the history as it is instead of marching again.
  uint64_t march_state = 0;
  int march_state_frames = 0;
  // The same digest without the geometry's (the view, the field, the light, the shaders), and its
  // frames in a row: from the second on, the view is held and the resolve keeps its history unclipped
  // where the scene's depth is the one it was marched against (history_depth). A host's geometry is
  // never known unchanged (welkin/host/sky.h), so the geometry is judged by the depth it leaves, the
  // same for any program that shows the same camera and geometry.
  uint64_t view_state = 0;
  int view_state_frames = 0;
  // The scene's depth (reversed Z) each pixel of history_color[i] was last marched against, at the
  // march's size.
  std::unique_ptr<Texture> history_depth[2];
  int marches = 0;               // frames that marched (tests, stats)
  bool has_layers = false;       // some layer can hold cloud this frame
  CloudsContext context;         // this frame's
  int clusters_layer = -1;       // the packed layer the mesh clusters draw (-1: none)
  float clusters_near_m = 0.0f;  // where the march hands it over this frame (clouds.CloudLod moves it)
  float lod_near_m = -1.0f;      // the budget's hand-over, carried between frames (-1: not started)
  ClustersGpu clusters;
  int billboards_layer = -1;        // the packed layer the billboards draw (-1: none)
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

}  // namespace welkin::clouds
