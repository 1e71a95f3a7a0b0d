// The march's empty-space skipping from the last frame's first cloud (first_hit_skip.h).
#include "first_hit_skip.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "clouds_gpu.h"
#include "welkin/core/type_id.h"
#include "welkin/gfx/compute.h"

namespace welkin::clouds {

namespace {

// The field without its drift: the layers with their noises' origins left out, the noise and map
// builds, the shaders' permutation.
uint64_t field_digest(const CloudsGpu& gpu, const ShaderDefines& defines) {
  uint64_t h = fnv1a_64_of(gpu.noise_builds, fnv1a_64_of(gpu.noise_seed));
  h = fnv1a_64_of(gpu.noise_cache_reads, fnv1a_64_of(gpu.coverage_map_revision, h));
  for (LayerBlock layer : gpu.layers) {
    layer.weather_origin = glm::vec3(0.0f);
    layer.streak_shape_origin = layer.streak_detail_origin = glm::vec3(0.0f);  // they move as the others do
    h = fnv1a_64_of(layer, h);
  }
  const FrameBlock& b = gpu.block;
  const float kept[] = {b.layer_count, b.system_amount, b.turbulence_m, b.scattering, b.absorption,
                        b.shape_per_m, b.detail_per_m, b.system_per_m, b.has_map, b.map_raise};
  h = fnv1a_64_of(kept, h);
  for (const auto& [k, v] : defines) h = fnv1a_64(k + "=" + v + ";", h);
  return h;
}

// How far a noise with origin `now` (in periods, fractions) moved since `before`, in metres: the
// camera's move and the wind's drift together.
float moved_m(const glm::vec3& now, const glm::vec3& before, float per_m) {
  const glm::vec3 d = now - before;
  return glm::length(d - glm::floor(d + 0.5f)) / std::max(per_m, 1e-12f);
}

// The field's largest drift since the last frame, the camera's move included (a bound: what a
// noise's origin moved is the camera's move plus the noise's own drift).
float field_drift_m(const CloudsGpu& gpu, const FirstHitHistory& last) {
  const FrameBlock &b = gpu.block, &p = last.block;
  float m = std::max({moved_m(b.shape_origin, p.shape_origin, b.shape_per_m),
                      moved_m(b.detail_origin, p.detail_origin, b.detail_per_m),
                      moved_m(b.system_origin, p.system_origin, b.system_per_m)});
  for (size_t i = 0; i < gpu.layers.size() && i < last.layers.size(); ++i)
    m = std::max(m, moved_m(gpu.layers[i].weather_origin, last.layers[i].weather_origin,
                            gpu.layers[i].weather_per_m) *
                        gpu.layers[i].streak);  // a streaked weather moves `streak` times less along the wind
  return m;
}

}  // namespace

FirstHitSkip plan_first_hit_skip(CloudsGpu& gpu, bool enabled, bool partial, int w, int h,
                                 const glm::vec3& camera_moved_m, GLuint unit, ShaderDefines& defines) {
  FirstHitHistory& history = gpu.first_hit;
  FirstHitSkip skip;
  if (!enabled) {
    history.valid = false;
    return skip;
  }
  const int write = gpu.history_index, read = 1 - write;
  ensure_texture(history.clear[write],
                 {.width = w, .height = h, .format = TextureFormat::r32f, .linear_filter = false});
  const uint64_t field = field_digest(gpu, defines);
  const Texture* last = history.clear[read].get();
  skip.write = true;
  skip.read = partial && history.valid && history.field == field && last && last->desc().width == w &&
              last->desc().height == h;
  history.field = field;
  if (!skip.read) return skip;
  skip.margin_m = glm::length(camera_moved_m) + field_drift_m(gpu, history);
  skip.round = int(gpu.marches & 7);
  skip.unit = unit;
  skip.previous_view_projection = gpu.previous_view_projection;
  skip.camera_moved_m = camera_moved_m;
  defines.insert_or_assign("CLOUDS_SKIP", std::string("1"));
  defines.insert_or_assign("CLOUDS_UNIT_FIRST_HIT", std::to_string(unit));
  return skip;
}

void set_first_hit_uniforms(const Program& p, const FirstHitSkip& skip) {
  if (!skip.read) return;
  p.set("u_skip_previous_view_projection", skip.previous_view_projection);
  p.set("u_skip_camera_moved_m", skip.camera_moved_m);
  p.set("u_skip_margin_m", skip.margin_m);
  p.set("u_skip_round", skip.round);
}

void finish_first_hit(CloudsGpu& gpu, const FirstHitSkip& skip) {
  FirstHitHistory& history = gpu.first_hit;
  history.valid = skip.write;
  history.block = gpu.block;
  history.layers = gpu.layers;
}

}  // namespace welkin::clouds
