#pragma once
// What the cloud shaders see of a frame: the frame block and the packed layers every cloud shader
// reads (shaders/clouds/density.glsl), made by frame_block.cpp.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "noise_volumes.h"
#include "welkin/clouds/components.h"
#include "welkin/gfx/camera.h"

namespace welkin::clouds {

// std140 mirror of CloudsFrame (vec4 and mat4 only: no hidden padding).
struct FrameBlock {
  glm::vec4 planet{0.0f};  // planet radius m, camera altitude m, camera radius m, layer count
  glm::vec4 up{0.0f};      // planet-centred up at the camera; w: max march distance m
  glm::vec4 shell{
      0.0f};  // lowest base, highest top (altitude m), empty-space step m, largest occupancy block m
  glm::vec4 shape_origin{0.0f};  // camera in shape periods (fraction); w: 1 / period
  glm::vec4 detail_origin{0.0f};
  glm::vec4 steps{0.0f};   // max steps, min step m, max step m, light steps
  glm::vec4 light{0.0f};   // first light step m, octaves, powder, ground albedo
  glm::vec4 medium{0.0f};  // scattering, absorption, phase model, droplet diameter um
  glm::vec4 phase{0.0f};   // g forward, g backward, forward weight, light marched (0 sun, 1 moon)
  glm::vec4 frame{0.0f};   // frame index, shape detail, march width, march height
  glm::vec4 light_model{
      0.0f};  // multiple scattering (0 octaves, 1 diffusion), march pixel angle, bands, step growth
  glm::vec4 band_low{0.0f};  // altitude bands holding layers (m, at most kMaxBands)
  glm::vec4 band_high{0.0f};
  // The painted coverage map's frame (welkin/scene/painted_map.h), relative to the planet's centre.
  glm::vec4 map_east{0.0f};    // east at the map's centre; w: planet radius / map side
  glm::vec4 map_north{0.0f};   // w: the largest coverage the map adds
  glm::vec4 map_up{0.0f};      // w: 1 when the scene has a map
  glm::vec4 map_origin{0.0f};  // the camera in (east, north, up) from the planet's centre, m
  glm::vec4 noise_mix{
      0.0f};  // largest displacement of the detail noise by the curl field m (0: off), weather-system amount
  glm::vec4 weather_system{0.0f};  // the camera in weather-system periods (fraction; the scene's origin at
                                   // the anchor, drift applied); w: 1 / period
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

// Coverage a painted map texel adds (128 nothing, 255 +1, 0 about -1).
inline double painted_coverage_offset(double texel) {
  return (texel - 128.0) / 127.0;
}

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
PackedLayers pack_layers(const VolumetricClouds& clouds, const CloudsContext& context,
                         const glm::dvec3& camera_m);
FrameBlock make_frame_block(const VolumetricClouds& clouds, const CloudsContext& context,
                            const NoiseFacts& noise, const FrameView& view, const PackedLayers& layers,
                            int march_width, int march_height, uint64_t frame_index);
// The shape model of a genus: dome (0 sheet .. 1 dome) and weather frequency relative to the period.
struct GenusModel {
  float dome;
  float weather_frequency;
};
GenusModel genus_model(Genus genus);

}  // namespace welkin::clouds
