// The shadow cascades (shadow_cascades.h): placed each frame, remade on the GPU only when what they
// show has changed, before the geometry.
#include "shadow_cascades.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "clouds_gpu.h"
#include "density_field.h"
#include "frame_upload.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

namespace {

constexpr int kShadowSteps = 40;

}  // namespace

void place_shadow_cascades(CloudsGpu& gpu, const VolumetricClouds& clouds, const CloudsContext& ctx,
                           const PackedLayers& layers, const FrameBlock& block, const FrameView& view) {
  // The shadow map: a square around the camera across the sun's direction, anchored in the world
  // and rebuilt only when what it shows has changed (sun, settings, drift or camera by a texel).
  const glm::vec3 l = ctx.sun_direction;
  const int cascades = std::clamp(clouds.shadow_cascades, 1, kMaxShadowCascades);
  ShadowKey key;
  key.wanted = clouds.shadows && layers.any_shadow && l.z > 0.0f;
  key.sun = l;
  key.time_s = ctx.time_s;
  key.anchor_m = view.camera_position_m;
  key.size = clouds.shadow_map_size;
  key.max_wind_mps = glm::length(clouds.wind_mps);
  for (const LayerBlock& b : layers.layers) {
    key.settings.insert(key.settings.end(),
                        {b.base_m, b.thickness_m, b.base_variation_m, b.density_per_m, b.coverage,
                         b.shape_amount, b.detail_amount, b.filter_width, b.profile_exp_term,
                         b.profile_exponent, b.profile_linear_term, b.profile_constant_term, b.dome,
                         b.weather_channel, b.casts_shadow, b.follows_map, b.billow, b.wisp, b.edge});
    key.settings.insert(key.settings.end(), {b.streak, b.hook_m, b.streak_axis.x, b.streak_axis.y,
                                             b.anvil_start, b.anvil_spread});
  }
  for (const CloudLayer& L : clouds.layers)
    key.max_wind_mps = std::max(key.max_wind_mps, glm::length(L.wind_mps));
  key.settings.insert(
      key.settings.end(),
      {block.scattering, block.absorption, float(clouds.seed), clouds.shape_period_m, clouds.weather_period_m,
       clouds.shadow_distance_m, float(cascades), block.has_map, float(ctx.coverage_map_revision & 0xffffffu),
       clouds.coverage_map_size_m, clouds.weather_system_amount, clouds.weather_system_period_m});
  // Cascade k (0 nearest) covers a square of side 2 D / 4^(n - 1 - k) around the camera; each is
  // remade on its own, when it is stale at its own texel size (the nearest follows the camera most).
  const glm::vec3 u =
      glm::normalize(glm::cross(l, std::abs(l.z) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
  const glm::vec3 v = glm::cross(l, u);
  const float start =
      std::max((layers.highest_shadow_m - block.camera_altitude_m) / std::max(l.z, 0.05f), 0.0f) + 100.0f;
  for (int k = 0; k < kMaxShadowCascades; ++k) {
    ShadowKey& held = gpu.shadow_keys[k];
    gpu.shadow_rebuild[k] = false;
    if (!key.wanted || k >= cascades) {
      held.wanted = false;
      gpu.shadow.cascades[k].valid = 0;
      continue;
    }
    const float side = 2.0f * clouds.shadow_distance_m / float(1 << (2 * (cascades - 1 - k)));
    ShadowKey cascade = key;
    cascade.texel_m = side / float(clouds.shadow_map_size);
    gpu.shadow_rebuild[k] = !held.wanted || held.stale(cascade);
    if (gpu.shadow_rebuild[k]) {
      gpu.shadow.cascades[k].axis_u = u / side;
      gpu.shadow.cascades[k].start_m = start;
      gpu.shadow.cascades[k].axis_v = v / side;
      gpu.shadow.cascades[k].side_m = side;
      held = cascade;
    }
    // A cascade stays where it was made: its centre, relative to this frame's camera.
    gpu.shadow.cascades[k].origin = glm::vec3(held.anchor_m - view.camera_position_m);
    gpu.shadow.cascades[k].valid = 1;
  }
  gpu.shadow_altitudes_m = {layers.lowest_shadow_m, layers.highest_shadow_m};
  gpu.shadow.deck_base_m = layers.lowest_deck_m, gpu.shadow.deck_top_m = layers.highest_deck_m;
  gpu.shadow.light = l;
  gpu.shadow.column_vertical = std::abs(l.z);
  gpu.shadow.up = block.up;
  gpu.shadow.cascade_count = key.wanted ? cascades : 0;
}

// Before the geometry: noise, this frame's block, and the shadow map every material reads.
void shadow_system(SystemContext& sc) {
  World& world = sc.world;
  const VolumetricClouds* clouds = first_clouds(world);
  if (!clouds) return;
  auto& gpu = world.resource<CloudsGpu>();
  ensure_noise(world, clouds->seed);
  gpu.has_layers = upload_frame(world, sc, *clouds, gpu.block);
  if (!gpu.has_layers || gpu.shadow.cascade_count < 1) {
    gpu.shadow.cascade_count = 0;
    for (ShadowKey& k : gpu.shadow_keys) k.wanted = false;
    return;
  }
  const int cascades = gpu.shadow.cascade_count, size = clouds->shadow_map_size;
  // The cascades side by side in one texture, nearest first, each column's four quarters (the body's
  // two halves, the direct beam's two: clouds/shadow_column.glsl) one above the other; a new texture
  // holds none of them yet.
  if (ensure_texture(gpu.shadow_map,
                     {.width = size * cascades, .height = 4 * size, .format = TextureFormat::rgba32f}))
    for (int k = 0; k < cascades; ++k) gpu.shadow_rebuild[k] = true;
  if (std::none_of(gpu.shadow_rebuild, gpu.shadow_rebuild + cascades, [](bool b) { return b; })) return;
  const ResourceHandle map = sc.graph->import("clouds.shadow_map", *gpu.shadow_map);
  auto& rc = world.resource<RenderContext>();
  CloudsGpu* gp = &gpu;
  const ShadowBlock s = gpu.shadow;
  std::vector<int> remade;
  for (int k = 0; k < cascades; ++k)
    if (gpu.shadow_rebuild[k]) remade.push_back(k);
  sc.graph->add_pass(
      "clouds.shadow_map",
      [&](PassBuilder& b) {
        b.write(map);
        b.side_effect();  // read by every material through the light environment
      },
      [gp, &rc, s, remade, size, altitudes = gpu.shadow_altitudes_m,
       decks = glm::vec2(gpu.shadow.deck_base_m, gpu.shadow.deck_top_m),
       defines = field_defines(gpu)](PassContext&) {
        bind_field(*gp);
        bind_image_for_write(0, *gp->shadow_map);
        const Program& p = rc.shaders.compute("clouds/shadow_map.comp", defines);
        for (int k : remade) {
          const gpu_blocks::CloudsShadowCascade& c = s.cascades[k];
          // The plane through the cascade's centre (camera-relative, this frame).
          p.set("u_centre", c.origin);
          p.set("u_light", s.light);
          p.set("u_axis_u", c.axis_u * c.side_m);
          p.set("u_axis_v", c.axis_v * c.side_m);
          p.set("u_extent_m", c.side_m);
          p.set("u_start_m", c.start_m);
          p.set("u_steps", kShadowSteps);
          p.set("u_altitudes_m", altitudes);
          p.set("u_deck_m", decks);
          glProgramUniform2i(p.id(), p.location("u_region"), k * size, size);
          const int g = group_count(size, 8);
          dispatch_compute(p, g, g);
          ++gp->shadow_builds;
        }
      });
}

}  // namespace welkin::clouds
