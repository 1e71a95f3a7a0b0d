// What the cloud shaders see of a frame: the layers that can hold cloud, packed, and the frame block.
// Positions that tile (noise coordinates) are reduced modulo their period in double precision here,
// so the GPU adds only camera-relative offsets in float, at any distance from the scene origin.
#include "frame_block.h"

#include <algorithm>
#include <cmath>

#include "welkin/scene/painted_map.h"

namespace welkin::clouds {

namespace {

// The fractional part of a position in periods, as float.
glm::vec3 tile_origin(const glm::dvec3& p_m, double period_m) {
  glm::dvec3 q = p_m / period_m;
  return glm::vec3(q - glm::floor(q));
}

// A position in a genus's streaked frame (density.glsl's clouds_streaked): stretched by `streak` along
// the unit `axis` (the noise varies `streak` times more slowly along the wind).
glm::dvec3 streaked(const glm::dvec3& p_m, const glm::dvec3& axis, double streak) {
  return p_m - axis * (glm::dot(p_m, axis) * (1.0 - 1.0 / streak));
}

}  // namespace

std::vector<glm::vec2> altitude_bands(std::vector<glm::vec2> ranges, int max_bands) {
  std::sort(ranges.begin(), ranges.end(), [](const glm::vec2& a, const glm::vec2& b) { return a.x < b.x; });
  std::vector<glm::vec2> bands;
  for (const glm::vec2& r : ranges) {
    if (!bands.empty() && r.x <= bands.back().y)
      bands.back().y = std::max(bands.back().y, r.y);
    else
      bands.push_back(r);
  }
  while (int(bands.size()) > max_bands) {
    size_t closest = 0;
    for (size_t i = 1; i + 1 < bands.size(); ++i)
      if (bands[i + 1].x - bands[i].y < bands[closest + 1].x - bands[closest].y) closest = i;
    bands[closest].y = bands[closest + 1].y;
    bands.erase(bands.begin() + long(closest) + 1);
  }
  return bands;
}

GenusModel genus_model(Genus genus) {
  const GenusTraits& g = genus_traits(genus);
  GenusModel m{g.dome, g.weather_frequency, g.billow, g.wisp, g.edge};
  m.streak = g.streak, m.hook_s = g.hook_s, m.anvil_start = g.anvil_start, m.anvil_spread = g.anvil_spread;
  return m;
}

PackedLayers pack_layers(const VolumetricClouds& clouds, const CloudsContext& ctx,
                         const glm::dvec3& camera_m) {
  PackedLayers out;
  const glm::dvec3 p = camera_m - ctx.planet_center_m;
  bool first = true, first_shadow = true;
  const bool any_solo =
      std::any_of(clouds.layers.begin(), clouds.layers.end(), [](const CloudLayer& L) { return L.solo; });
  for (size_t i = 0; i < clouds.layers.size(); ++i) {
    const CloudLayer& L = clouds.layers[i];
    if (!L.visible || (any_solo && !L.solo)) continue;
    const float coverage = std::clamp(L.coverage * clouds.coverage, 0.0f, 1.0f);
    // A layer that cannot hold cloud is not marched at all (a painted map may add coverage to one).
    const bool follows_map = L.follows_coverage_map && ctx.has_coverage_map;
    const bool can_cover = coverage > 0.0f || (follows_map && coverage + ctx.coverage_map_raise > 0.0f);
    if (!(L.thickness_m > 0.0f) || !can_cover || !(L.density_per_m > 0.0f)) continue;
    const GenusModel g = genus_model(L.genus);
    const double period = double(clouds.weather_period_m) / g.weather_frequency;
    // Layers i, i + 1, i + 2 read three independent channels at one place (one fetch serves them when
    // their genus and wind agree); every further three read another part of the volume.
    const double group = double(i / 3);
    const glm::dvec3 offset = glm::dvec3(0.37 * group, 0.61 * group, 0.13 * group) * period;
    const glm::dvec3 drift = glm::dvec3(L.wind_mps, 0.0) * ctx.time_s;
    LayerBlock b{};
    b.base_m = L.base_altitude_m, b.thickness_m = L.thickness_m;
    b.base_variation_m = L.base_variation_m, b.density_per_m = L.density_per_m;
    b.coverage = coverage, b.shape_amount = L.shape_amount, b.detail_amount = L.detail_amount;
    b.filter_width = std::max(L.coverage_filter_width, 0.01f);
    b.profile_exp_term = L.profile_exp_term, b.profile_exponent = L.profile_exponent;
    b.profile_linear_term = L.profile_linear_term, b.profile_constant_term = L.profile_constant_term;
    b.weather_per_m = float(1.0 / period);
    b.dome = g.dome, b.weather_channel = float(i % 3);
    b.billow = g.billow, b.wisp = g.wisp, b.edge = g.edge;
    // Streaks along the layer's wind, their noise's origins in the streaked frame (the shape and
    // detail noise drift with the clouds' wind); an anvil under the layer's ceiling.
    const double wind = glm::length(glm::dvec2(L.wind_mps));
    const glm::dvec3 axis = wind > 0.0 ? glm::dvec3(glm::dvec2(L.wind_mps) / wind, 0.0) : glm::dvec3(0.0);
    const glm::dvec3 noise_p = p - glm::dvec3(clouds.wind_mps, 0.0) * ctx.time_s;
    // Without wind there is no direction to streak along: such a layer packs streak 1 and no hook, so
    // that the field compiles no streak code for it (density_field.cpp) and it shares its weather
    // sample with the layers of its place (the stretch along no axis is the identity anyway).
    b.streak_axis = glm::vec3(axis), b.streak = wind > 0.0 ? std::max(g.streak, 1.0f) : 1.0f;
    b.hook_m = float(g.hook_s * wind);
    b.streak_shape_origin = tile_origin(streaked(noise_p, axis, b.streak), clouds.shape_period_m);
    b.streak_detail_origin = tile_origin(streaked(noise_p, axis, b.streak), clouds.detail_period_m);
    b.weather_origin = tile_origin(streaked(p - drift + offset, axis, b.streak), period);
    b.anvil_start = g.anvil_start, b.anvil_spread = g.anvil_spread;
    b.casts_shadow = L.casts_shadow ? 1.0f : 0.0f, b.follows_map = follows_map ? 1.0f : 0.0f;
    out.layers.push_back(b);
    out.source_index.push_back(int(i));
    const float lo = L.base_altitude_m - L.base_variation_m,
                hi = L.base_altitude_m + L.thickness_m + L.base_variation_m;
    out.ranges.push_back({lo, hi});
    out.lowest_m = first ? lo : std::min(out.lowest_m, lo);
    out.highest_m = first ? hi : std::max(out.highest_m, hi);
    first = false;
    if (L.casts_shadow) {
      out.lowest_shadow_m = first_shadow ? lo : std::min(out.lowest_shadow_m, lo);
      out.highest_shadow_m = first_shadow ? hi : std::max(out.highest_shadow_m, hi);
      first_shadow = false;
      out.any_shadow = true;
    }
  }
  // A layer that casts no shadow above every one that does (cirrus over cumulus) still dims the sun
  // that reaches them: the shadow map integrates it apart (CloudsShadowColumn.far.w). One between or under
  // the casters (a haze at the ground) is not in the map at all.
  bool first_deck = true;
  for (size_t i = 0; i < out.layers.size() && out.any_shadow; ++i) {
    const glm::vec2 r = out.ranges[i];
    if (out.layers[i].casts_shadow > 0.5f || r.x < out.highest_shadow_m) continue;
    out.lowest_deck_m = first_deck ? r.x : std::min(out.lowest_deck_m, r.x);
    out.highest_deck_m = first_deck ? r.y : std::max(out.highest_deck_m, r.y);
    first_deck = false;
  }
  return out;
}

FrameBlock make_frame_block(const VolumetricClouds& clouds, const CloudsContext& ctx, const NoiseFacts& noise,
                            const FrameView& view, const PackedLayers& layers, int march_width,
                            int march_height, uint64_t frame_index) {
  const ResolvedQuality q = resolve_quality(clouds);
  const glm::dvec3 p = view.camera_position_m - ctx.planet_center_m;
  const double r = std::max(glm::length(p), 1.0);
  const glm::dvec3 drift = glm::dvec3(clouds.wind_mps, 0.0) * ctx.time_s;
  FrameBlock f{};
  f.planet_radius_m = float(ctx.planet_radius_m), f.camera_altitude_m = float(r - ctx.planet_radius_m);
  f.camera_radius_m = float(r), f.layer_count = float(layers.layers.size());
  f.up = glm::vec3(p / r), f.max_distance_m = clouds.max_distance_m;
  // The empty-space step, a quarter of the finest weather texel of the layers.
  float finest_weather_m = clouds.weather_period_m;
  for (const LayerBlock& b : layers.layers)
    finest_weather_m = std::min(finest_weather_m, 1.0f / b.weather_per_m);
  float largest_block_m = 0.0f;
  for (const LayerBlock& b : layers.layers)
    largest_block_m = std::max(largest_block_m, 1.0f / (b.weather_per_m * float(kWeatherOccupancySize)));
  f.lowest_m = layers.lowest_m, f.highest_m = layers.highest_m;
  f.empty_step_m = 0.25f * finest_weather_m / float(kWeatherNoiseSize), f.largest_block_m = largest_block_m;
  f.shape_origin = tile_origin(p - drift, clouds.shape_period_m),
  f.shape_per_m = 1.0f / clouds.shape_period_m;
  f.detail_origin = tile_origin(p - drift, clouds.detail_period_m),
  f.detail_per_m = 1.0f / clouds.detail_period_m;
  f.max_steps = float(q.max_steps), f.min_step_m = q.min_step_m, f.max_step_m = q.max_step_m;
  f.light_steps = float(q.light_steps);
  f.light_step_m = q.light_step_m, f.octaves = float(clouds.multiscattering_octaves),
  f.powder = clouds.powder;
  f.ground_albedo = clouds.ground_albedo;
  f.scattering = clouds.scattering_coefficient, f.absorption = clouds.absorption_coefficient;
  f.phase_model = float(int(clouds.phase)), f.droplet_diameter_um = clouds.droplet_diameter_um;
  f.g_forward = clouds.phase_g_forward, f.g_backward = clouds.phase_g_backward,
  f.forward_weight = clouds.phase_mix;
  f.moon_marched = ctx.sun_up_for_clouds ? 0.0f : 1.0f;
  f.frame_index = float(frame_index % 1024), f.shape_detail = q.shape_detail ? 1.0f : 0.0f;
  f.march_width = float(march_width), f.march_height = float(march_height);
  const std::vector<glm::vec2> bands = altitude_bands(layers.ranges);
  f.multiple_scattering = float(int(clouds.multiple_scattering));
  f.pixel_angle_rad = view.vertical_fov_rad / float(std::max(march_height, 1));
  f.band_count = float(bands.size()), f.step_growth = q.step_growth;
  for (size_t i = 0; i < bands.size(); ++i) f.band_low[int(i)] = bands[i].x, f.band_high[int(i)] = bands[i].y;
  const MapFrame map{ctx.planet_center_m, ctx.planet_radius_m, clouds.coverage_map_size_m};
  const glm::dmat3 axes = map.axes();
  f.map_east = glm::vec3(axes[0]), f.map_scale = float(ctx.planet_radius_m / map.size_m);
  f.map_north = glm::vec3(axes[1]), f.map_raise = ctx.coverage_map_raise;
  f.map_up = glm::vec3(axes[2]), f.has_map = ctx.has_coverage_map ? 1.0f : 0.0f;
  f.map_origin = glm::vec3(glm::transpose(axes) * p);
  f.turbulence_m = q.turbulence ? clouds.turbulence_displacement_m : 0.0f;
  f.system_amount = clouds.weather_system_amount;
  // The scene's origin sits at the anchor texel, whose signal is neutral; the systems stay where they
  // are (the wind moves the clouds through them), so the origin keeps its layers' own coverage.
  const double system_period = clouds.weather_system_period_m;
  f.system_origin =
      tile_origin(view.camera_position_m + glm::dvec3(noise.system_anchor) * system_period, system_period);
  f.system_per_m = float(1.0 / system_period);
  // The most the signal changes per metre (a linear filter's gradient is at most sqrt(3) x the
  // largest step between neighbouring texels per texel): a bound for the empty-space skipping.
  f.system_slope_per_m = float(1.75 * noise.weather_step * kSystemsNoiseSize / system_period);
  // Every layer handed over to the mesh clusters as far as the march reaches: it need not reach
  // past the hand-over.
  float handed_over_m = 0.0f;
  for (const LayerBlock& b : layers.layers)
    handed_over_m = b.handover_near_m > 0.0f && b.handover_far_m >= clouds.max_distance_m
                        ? std::max(handed_over_m, b.handover_near_m + 0.5f * b.handover_crossfade_m)
                        : 3.4e38f;
  if (!layers.layers.empty()) f.max_distance_m = std::min(f.max_distance_m, handed_over_m);
  f.inverse_view_projection = view.inverse_view_projection;
  return f;
}

}  // namespace welkin::clouds
