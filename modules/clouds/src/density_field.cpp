// The density field as shaders include it (shaders/clouds/density.glsl): its bindings, and the
// compile-time description of this frame's layers and light model.
#include "density_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace welkin::clouds {

void bind_field(const CloudsGpu& gpu) {
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, gpu.frame_buffer->id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gpu.layer_buffer->id());
  glBindTextureUnit(0, gpu.shape->id());
  glBindTextureUnit(1, gpu.detail->id());
  glBindTextureUnit(2, gpu.weather->id());
  glBindTextureUnit(5, gpu.weather_maximum->id());
  glBindTextureUnit(6, gpu.coverage_map->id());
  glBindTextureUnit(7, gpu.systems->id());
}

ShaderDefines light_model_defines(const CloudsGpu& gpu) {
  ShaderDefines d = {{"CLOUDS_MULTIPLE_SCATTERING", gpu.block.multiple_scattering > 0.5f ? "1" : "0"},
                     {"CLOUDS_POWDER", gpu.block.powder != 0.0f ? "1" : "0"},
                     {"CLOUDS_PHASE_MODEL", gpu.block.phase_model > 0.5f ? "1" : "0"},
                     // The fitted weights differ with and without the detail noise (light_model_fit.glsl).
                     {"CLOUDS_SHAPE_DETAIL", gpu.block.shape_detail > 0.5f ? "1" : "0"}};
  for (const auto& [name, value] : gpu.light_model_fit) d[name] = value;
  return d;
}

// The density field's compile-time description (density.glsl): which layers there are and what each
// uses, so that no shader carries code for a layer's unused noise or a map the scene lacks. Up to
// CLOUDS_LOCAL_LAYERS layers; more are read with run-time checks.
ShaderDefines field_defines(const CloudsGpu& gpu) {
  constexpr int kLocalLayers = 4;
  ShaderDefines d = {{"CLOUDS_TURBULENCE", gpu.block.turbulence_m > 0.0f ? "1" : "0"}};
  if (gpu.clusters_layer >= 0 || gpu.billboards_layer >= 0) d["CLOUDS_HANDOVER"] = "1";
  const std::vector<LayerBlock>& layers = gpu.layers;
  // The genera's streaks and anvils (genera.h) compile in only when some layer has them.
  const auto streaks = [](const LayerBlock& L) { return L.streak > 1.0f || L.hook_m != 0.0f; };
  const auto anvil = [](const LayerBlock& L) { return L.anvil_start > 0.0f; };
  d["CLOUDS_STREAKS"] = std::any_of(layers.begin(), layers.end(), streaks) ? "1" : "0";
  d["CLOUDS_ANVILS"] = std::any_of(layers.begin(), layers.end(), anvil) ? "1" : "0";
  if (layers.empty() || layers.size() > size_t(kLocalLayers)) return d;
  const bool detail = gpu.block.shape_detail > 0.5f, map = gpu.block.has_map > 0.5f;
  int detail_mask = 0, map_mask = 0, shadow_mask = 0, streak_mask = 0, anvil_mask = 0;
  for (size_t i = 0; i < layers.size(); ++i) {
    const LayerBlock& L = layers[i];
    if (detail && L.detail_amount > 0.0f) detail_mask |= 1 << i;
    if (map && L.follows_map > 0.5f) map_mask |= 1 << i;
    if (L.casts_shadow > 0.5f) shadow_mask |= 1 << i;
    if (streaks(L)) streak_mask |= 1 << i;
    if (anvil(L)) anvil_mask |= 1 << i;
    // The first layer with the same weather origin and period (the same place: one fetch, other channels).
    size_t source = i;
    for (size_t j = 0; j < i && source == i; ++j)
      if (layers[j].weather_origin == L.weather_origin && layers[j].weather_per_m == L.weather_per_m &&
          layers[j].streak == L.streak && layers[j].streak_axis == L.streak_axis)
        source = j;
    if (i > 0) d["CLOUDS_WEATHER_SOURCE_" + std::to_string(i)] = std::to_string(source);
  }
  for (size_t i = layers.size(); i < size_t(kLocalLayers); ++i)
    if (i > 0) d["CLOUDS_WEATHER_SOURCE_" + std::to_string(i)] = std::to_string(i);
  d["CLOUDS_LAYERS"] = std::to_string(layers.size());
  d["CLOUDS_DETAIL_MASK"] = std::to_string(detail_mask);
  d["CLOUDS_MAP_MASK"] = std::to_string(map_mask);
  d["CLOUDS_SHADOW_MASK"] = std::to_string(shadow_mask);
  d["CLOUDS_STREAK_MASK"] = std::to_string(streak_mask);
  d["CLOUDS_ANVIL_MASK"] = std::to_string(anvil_mask);
  return d;
}

// A layer outside a band's reach adds nothing to its samples (density.glsl returns 0 outside a layer's
// altitudes), so leaving it out of that band's march changes no pixel; a software rasteriser would
// otherwise run its code, and read its weather, at every sample and light step of every band (the peer
// scene's haze at the ground paid for the cumulus and the cirrus at each of its samples).
ShaderDefines band_defines(const CloudsGpu& gpu) {
  constexpr int kLocalLayers = 4, kMaxBands = 4;
  const std::vector<LayerBlock>& layers = gpu.layers;
  const FrameBlock& b = gpu.block;
  const int bands = int(b.band_count);
  // Light steps double from the first (light_march.glsl): past 20 they reach every layer anyway.
  if (layers.empty() || layers.size() > size_t(kLocalLayers) || bands < 1 || bands > kMaxBands ||
      b.light_steps > 20.0f)
    return {};
  // How far the light steps reach (their last sample lies within light_step x 2^steps; the side
  // probes, level, one first step away), up and down: along the marched light, whose angle to a
  // sample's vertical differs from its angle at the camera by at most the angle the planet's centre
  // sees between them: the farthest sample lies beyond where the ray enters the highest band (the
  // horizon's distance from both) by the march's maximum distance, and a degree more (the shaders'
  // light and this frame's sun come from one source; a margin all the same). The moon's direction is
  // not known here: both ways.
  const double reach = double(b.light_step_m) * std::exp2(double(b.light_steps));
  const double R = b.planet_radius_m, top = std::max(double(b.band_high[bands - 1]), 0.0);
  const double camera = std::max(double(b.camera_altitude_m), 0.0);
  const double farthest = std::sqrt(top * (2.0 * R + top)) + std::sqrt(camera * (2.0 * R + camera)) +
                          double(b.max_distance_m);
  const double spread = 2.0 * std::asin(std::min(farthest / (2.0 * R), 1.0)) + std::numbers::pi / 180.0;
  double up = reach, down = reach;
  if (b.moon_marched < 0.5f) {
    const glm::dvec3 l = glm::normalize(glm::dvec3(gpu.context.sun_direction));
    const double angle = std::acos(std::clamp(glm::dot(l, glm::dvec3(b.up)), -1.0, 1.0));
    up = reach * std::max(std::cos(std::max(angle - spread, 0.0)), 0.0);
    down = reach * std::max(-std::cos(std::min(angle + spread, std::numbers::pi)), 0.0);
  }
  ShaderDefines d = {{"CLOUDS_BANDS", std::to_string(bands)}};
  for (int k = 0; k < bands; ++k) {
    // A metre and a part in 10^4 more: the band's samples are placed in float.
    const double margin = 1.0 + 1e-4 * (std::abs(double(b.band_high[k])) + reach);
    const double lo = double(b.band_low[k]) - down - margin, hi = double(b.band_high[k]) + up + margin;
    int mask = 0;
    for (size_t i = 0; i < layers.size(); ++i) {
      const LayerBlock& L = layers[i];
      const double from = double(L.base_m) - L.base_variation_m,
                   to = double(L.base_m) + L.thickness_m + L.base_variation_m;
      if (to >= lo && from <= hi) mask |= 1 << i;
    }
    d["CLOUDS_BAND_LAYERS_" + std::to_string(k)] = std::to_string(mask);
  }
  return d;
}

}  // namespace welkin::clouds
