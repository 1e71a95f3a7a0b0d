// This frame's block and layers (frame_upload.h): what the clouds read of the scene, packed and
// uploaded.
#include "frame_upload.h"

#include <algorithm>
#include <cmath>

#include "coverage_map.h"
#include "layer_handover.h"
#include "shadow_cascades.h"
#include "welkin/core/world.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/painted_map.h"
#include "welkin/scene/shared_state.h"

namespace welkin::clouds {

namespace {

// The planet, the time and the sun, from the world's shared state (welkin/scene/shared_state.h).
CloudsContext read_context(World& world, const FrameInfo& frame) {
  CloudsContext c;
  const MapFrame planet = scene_map_frame(world, 1.0);
  c.planet_radius_m = planet.planet_radius_m;
  c.planet_center_m = planet.planet_center_m;
  // Wind follows the time of day when there is one, so scrubbing a sequence equals playing it.
  const SceneTime* clock = world.find_resource<SceneTime>();
  c.time_s = clock && clock->present ? clock->local_time_h * 3600.0 : frame.time_s;
  if (auto sun = scene_sun_direction(world)) c.sun_direction = *sun;
  // Cloud tops at 10 km still see a sun 3 degrees below the horizon; below ~10 degrees the moon
  // (when the scene has one) is the light worth marching toward.
  const LightSources* lights = world.find_resource<LightSources>();
  const bool has_moon = lights && lights->scene.moon.present;
  c.sun_up_for_clouds = !has_moon || c.sun_direction.z > -0.17f;
  return c;
}

}  // namespace

const VolumetricClouds* first_clouds(World& world) {
  Registry& reg = world.registry();
  const Entity e = reg.first<VolumetricClouds>();
  return e.is_null() ? nullptr : reg.get<VolumetricClouds>(e);
}

bool camera_in_space(World& world, const FrameBlock& f) {
  const PlanetFrame* planet = world.find_resource<PlanetFrame>();
  return planet && planet->atmosphere_top_m && double(f.camera_radius_m) > *planet->atmosphere_top_m;
}

// Uploads this frame's block and layers; false when no layer can hold cloud (nothing to draw).
bool upload_frame(World& world, const SystemContext& sc, const VolumetricClouds& clouds, FrameBlock& block) {
  check_component(clouds);
  auto& gpu = world.resource<CloudsGpu>();
  const FrameView& view = world.resource<RenderContext>().view;
  CloudsContext ctx = read_context(world, sc.frame);
  upload_coverage_map(world, clouds, gpu, ctx);
  PackedLayers layers = pack_layers(clouds, ctx, view.camera_position_m);
  hand_over_layers(world, sc, gpu, layers);
  gpu.context = ctx;
  const ResolvedQuality q = resolve_quality(clouds);
  const int w = std::max(1, int(std::ceil(view.width * q.resolution_scale)));
  const int h = std::max(1, int(std::ceil(view.height * q.resolution_scale)));
  block = make_frame_block(clouds, ctx, gpu.noise_facts, view, layers, w, h, sc.frame.index);
  if (!gpu.frame_buffer) gpu.frame_buffer = std::make_unique<Buffer>(sizeof(FrameBlock));
  gpu.frame_buffer->upload(&block, sizeof(block));
  const size_t count = std::max<size_t>(layers.layers.size(), 1);
  if (!gpu.layer_buffer || gpu.layer_capacity < count) {
    gpu.layer_buffer = std::make_unique<Buffer>(count * sizeof(LayerBlock));
    gpu.layer_capacity = count;
  }
  if (!layers.layers.empty())
    gpu.layer_buffer->upload(layers.layers.data(), layers.layers.size() * sizeof(LayerBlock));
  gpu.layers = layers.layers;
  place_shadow_cascades(gpu, clouds, ctx, layers, block, view);
  return !layers.layers.empty();
}

}  // namespace welkin::clouds
