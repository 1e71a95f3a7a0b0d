// The density field as shaders include it (shaders/clouds/density.glsl): its bindings, and the
// compile-time description of this frame's layers and light model.
#include "density_field.h"

#include <algorithm>
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

}  // namespace welkin::clouds
