// The clouds' frame: noise generated once per seed, the beer shadow map before the geometry (every
// material reads it through the light environment), and after the geometry and its aerial
// perspective, the march at a fraction of the resolution and its composite over the frame.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "welkin/clouds/blue_noise.h"
#include "welkin/clouds/gpu.h"
#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/painted_map.h"

namespace welkin::clouds {

namespace {

constexpr int kShadowSteps = 40;

const VolumetricClouds* first_clouds(World& world) {
  Registry& reg = world.registry();
  const Entity e = reg.first<VolumetricClouds>();
  return e.is_null() ? nullptr : reg.get<VolumetricClouds>(e);
}

// The planet, the time and the sun, from whichever modules the scene has (through reflection).
CloudsContext read_context(World& world, const FrameInfo& frame) {
  CloudsContext c;
  const MapFrame planet = scene_map_frame(world, 1.0);
  c.planet_radius_m = planet.planet_radius_m;
  c.planet_center_m = planet.planet_center_m;
  // Wind follows the time of day when there is one, so scrubbing a sequence equals playing it.
  if (auto h = scene_scalar(world, "timeofday.TimeOfDay", "local_time_h")) c.time_s = *h * 3600.0;
  else c.time_s = frame.time_s;
  if (auto sun = scene_sun_direction(world)) c.sun_direction = *sun;
  // Cloud tops at 10 km still see a sun 3 degrees below the horizon; below ~10 degrees the moon
  // (when the scene has one) is the light worth marching toward.
  const bool has_moon = scene_scalar(world, "atmosphere.Moon", "illuminance_lux").has_value();
  c.sun_up_for_clouds = !has_moon || c.sun_direction.z > -0.17f;
  return c;
}

// An 8-bit volume's level 0, read back or uploaded (`size` bytes, tightly packed).
std::vector<uint8_t> read_volume(const Texture& volume, GLenum format, size_t size) {
  std::vector<uint8_t> data(size);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(volume.id(), 0, format, GL_UNSIGNED_BYTE, GLsizei(size), data.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  return data;
}

void upload_volume(Texture& volume, GLenum format, const std::vector<uint8_t>& data) {
  const TextureDesc& d = volume.desc();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(volume.id(), 0, 0, 0, 0, d.width, d.height, d.depth, format, GL_UNSIGNED_BYTE, data.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

// Equalises the first `equalised` channels of an 8-bit volume (GL_RGBA: 4 channels, GL_RED: 1) to a
// uniform distribution, so that a layer's coverage c covers a fraction c of the sky whatever the
// noise's own histogram.
std::vector<uint8_t> equalise(Texture& volume, GLenum format, int channels, int equalised) {
  const int n = volume.desc().width * volume.desc().height * volume.desc().depth;
  std::vector<uint8_t> data = read_volume(volume, format, size_t(n) * size_t(channels));
  for (int c = 0; c < equalised; ++c) {
    std::array<double, 256> histogram{};
    for (int i = 0; i < n; ++i) histogram[data[size_t(i) * size_t(channels) + size_t(c)]] += 1.0;
    std::array<uint8_t, 256> map{};
    double below = 0.0;
    for (int v = 0; v < 256; ++v) {
      map[size_t(v)] = uint8_t(std::lround(255.0 * (below + 0.5 * histogram[size_t(v)]) / n));
      below += histogram[size_t(v)];
    }
    for (int i = 0; i < n; ++i) data[size_t(i) * size_t(channels) + size_t(c)] = map[data[size_t(i) * size_t(channels) + size_t(c)]];
  }
  upload_volume(volume, format, data);
  return data;
}

// Packs the curl field into the shape volume's gba as 0.5 + 0.5 c, scaled so that its longest
// vector has length 1 (the displacement setting is then the largest distance the noise moves).
// Returns the shape's texels as stored.
std::vector<uint8_t> pack_turbulence(Texture& shape, const Texture& curl) {
  const TextureDesc& d = shape.desc();
  const size_t n = size_t(d.width) * size_t(d.height) * size_t(d.depth);
  std::vector<float> c(n * 4);
  glGetTextureImage(curl.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(c.size() * sizeof(float)), c.data());
  double longest = 0.0;
  for (size_t i = 0; i < n; ++i)
    longest = std::max(longest, std::sqrt(double(c[i * 4]) * c[i * 4] + double(c[i * 4 + 1]) * c[i * 4 + 1] +
                                          double(c[i * 4 + 2]) * c[i * 4 + 2]));
  if (!(longest > 0.0)) throw Error("clouds: the generated curl field is zero everywhere");
  std::vector<uint8_t> texels = read_volume(shape, GL_RGBA, n * 4);
  for (size_t i = 0; i < n; ++i)
    for (size_t a = 0; a < 3; ++a)
      texels[i * 4 + 1 + a] = uint8_t(std::lround(std::clamp(127.5 + 127.5 * c[i * 4 + a] / longest, 0.0, 255.0)));
  upload_volume(shape, GL_RGBA, texels);
  return texels;
}

// What the weather systems need of their (equalised, R8) volume: the largest step
// between neighbouring texels (across the wrap too), and the anchor: of the texels nearest the
// median (equalisation may skip levels), the one whose neighbourhood is flattest, so that the scene's
// origin and its surroundings keep their layers' own coverage.
NoiseFacts systems_facts(const std::vector<uint8_t>& v, int size) {
  auto at = [&](int x, int y, int z) {
    return int(v[(size_t((z + size) % size) * size + size_t((y + size) % size)) * size + size_t((x + size) % size)]);
  };
  NoiseFacts facts;
  int largest = 0;
  std::pair<int, int> best{1 << 30, 0};  // distance from the median (in half levels), spread
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const int v0 = at(x, y, z);
        const int dx = std::abs(at(x + 1, y, z) - v0), dy = std::abs(at(x, y + 1, z) - v0), dz = std::abs(at(x, y, z + 1) - v0);
        largest = std::max({largest, dx, dy, dz});
        const int spread = dx + dy + dz + std::abs(at(x - 1, y, z) - v0) + std::abs(at(x, y - 1, z) - v0) + std::abs(at(x, y, z - 1) - v0);
        const std::pair<int, int> score{std::abs(2 * v0 - 255), spread};
        if (score < best) best = score, facts.system_anchor = (glm::vec3(x, y, z) + 0.5f) / float(size);
      }
  facts.weather_step = float(largest) / 255.0f;
  return facts;
}

// The coarse occupancy the march skips empty space with: for each block of 4^3 weather texels, the
// largest coverage signal of each channel over the block and the texels a linear filter reads beside
// it. The march leaves a block whose maximum allows no cloud at the block's far side.
std::vector<uint8_t> weather_maximum(const std::vector<uint8_t>& weather, int size) {
  const int b = kWeatherOccupancySize, per = size / b;
  auto at = [&](int x, int y, int z, int c) {
    auto w = [size](int v) { return ((v % size) + size) % size; };
    return weather[((size_t(w(z)) * size + size_t(w(y))) * size + size_t(w(x))) * 4 + size_t(c)];
  };
  std::vector<uint8_t> out(size_t(b) * b * b * 4, 0);
  for (int z = 0; z < b; ++z)
    for (int y = 0; y < b; ++y)
      for (int x = 0; x < b; ++x)
        for (int c = 0; c < 3; ++c) {
          uint8_t m = 0;
          for (int k = -1; k <= per; ++k)
            for (int j = -1; j <= per; ++j)
              for (int i = -1; i <= per; ++i) m = std::max(m, at(x * per + i, y * per + j, z * per + k, c));
          out[((size_t(z) * b + y) * b + x) * 4 + size_t(c)] = m;
        }
  return out;
}

}  // namespace

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

// The density field's compile-time description (density.glsl): which layers there are and what each
// uses, so that no shader carries code for a layer's unused noise or a map the scene lacks. Up to
// CLOUDS_LOCAL_LAYERS layers; more are read with run-time checks.
ShaderDefines light_model_defines(const CloudsGpu& gpu) {
  return {{"CLOUDS_MULTIPLE_SCATTERING", gpu.block.light_model.x > 0.5f ? "1" : "0"},
          {"CLOUDS_POWDER", gpu.block.light.z != 0.0f ? "1" : "0"},
          {"CLOUDS_PHASE_MODEL", gpu.block.medium.z > 0.5f ? "1" : "0"}};
}

ShaderDefines field_defines(const CloudsGpu& gpu) {
  constexpr int kLocalLayers = 4;
  ShaderDefines d = {{"CLOUDS_TURBULENCE", gpu.block.noise_mix.x > 0.0f ? "1" : "0"}};
  if (gpu.clusters_layer >= 0 || gpu.billboards_layer >= 0) d["CLOUDS_HANDOVER"] = "1";
  const std::vector<LayerBlock>& layers = gpu.layers;
  if (layers.empty() || layers.size() > size_t(kLocalLayers)) return d;
  const bool detail = gpu.block.frame.y > 0.5f, map = gpu.block.map_up.w > 0.5f;
  int detail_mask = 0, map_mask = 0, shadow_mask = 0;
  for (size_t i = 0; i < layers.size(); ++i) {
    const LayerBlock& L = layers[i];
    if (detail && L.shape.z > 0.0f) detail_mask |= 1 << i;
    if (map && L.model.w > 0.5f) map_mask |= 1 << i;
    if (L.model.z > 0.5f) shadow_mask |= 1 << i;
    // The first layer with the same weather origin and period (the same place: one fetch, other channels).
    size_t source = i;
    for (size_t j = 0; j < i && source == i; ++j)
      if (layers[j].weather == L.weather) source = j;
    if (i > 0) d["CLOUDS_WEATHER_SOURCE_" + std::to_string(i)] = std::to_string(source);
  }
  for (size_t i = layers.size(); i < size_t(kLocalLayers); ++i)
    if (i > 0) d["CLOUDS_WEATHER_SOURCE_" + std::to_string(i)] = std::to_string(i);
  d["CLOUDS_LAYERS"] = std::to_string(layers.size());
  d["CLOUDS_DETAIL_MASK"] = std::to_string(detail_mask);
  d["CLOUDS_MAP_MASK"] = std::to_string(map_mask);
  d["CLOUDS_SHADOW_MASK"] = std::to_string(shadow_mask);
  return d;
}

namespace {

// The painted coverage map (the editor's brush), uploaded again only when a stroke changed it; a
// 1 x 1 neutral texel stands for none.
void upload_coverage_map(World& world, const VolumetricClouds& clouds, CloudsGpu& gpu, CloudsContext& ctx) {
  auto upload = [&gpu](int side, const uint8_t* texels) {
    ensure_texture(gpu.coverage_map, {.width = side, .height = side, .format = TextureFormat::r8});
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(gpu.coverage_map->id(), 0, 0, 0, side, side, GL_RED, GL_UNSIGNED_BYTE, texels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  };
  if (clouds.coverage_map.empty()) {
    if (!gpu.coverage_map || !gpu.coverage_map_file.empty()) {
      upload(1, &kPaintedMapNeutral);
      gpu.coverage_map_file.clear();
    }
    return;
  }
  const PaintedMap* map = nullptr;
  try {
    map = &world.resource<PaintedMaps>().get(clouds.coverage_map);
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(VolumetricClouds::kTypeName) + "/coverage_map");
  }
  if (gpu.coverage_map_file != clouds.coverage_map || gpu.coverage_map_revision != map->revision) {
    upload(map->side, map->texels.data());
    gpu.coverage_map_file = clouds.coverage_map;
    gpu.coverage_map_revision = map->revision;
    gpu.coverage_map_raise = float(painted_coverage_offset(map->maximum()));
  }
  ctx.has_coverage_map = true;
  ctx.coverage_map_raise = gpu.coverage_map_raise;
  ctx.coverage_map_revision = map->revision;
}

// Where the march hands the clusters' layer over this frame: the clusters' near_m, or with a
// clouds.CloudLod budget, last frame's distance moved by the clouds' measured GPU time.
float handover_distance(World& world, const SystemContext& sc, const CloudClusters& clusters, CloudsGpu& gpu) {
  Registry& reg = world.registry();
  const Entity le = reg.first<CloudLod>();
  const CloudLod* lod = le.is_null() ? nullptr : reg.get<CloudLod>(le);
  if (!lod || !(lod->budget_ms > 0.0f) || sc.frame.alone) {
    gpu.lod_near_m = -1.0f;
    return clusters.near_m;
  }
  check_component(*lod);
  const float lo = lod->min_near_m, hi = std::min(lod->max_near_m, std::max(clusters.far_m - clusters.crossfade_m, lo));
  if (gpu.lod_near_m < 0.0f) gpu.lod_near_m = std::clamp(clusters.near_m, lo, hi);
  double ms = 0.0;
  bool measured = false;
  for (const PassTiming& t : world.resource<RenderContext>().last_timings)
    if (t.system.rfind("clouds.", 0) == 0) ms += t.gpu_ms, measured = true;
  // Over budget: the clusters take over nearer; well under it (15% to spare): farther.
  if (measured && ms > lod->budget_ms) gpu.lod_near_m *= 1.0f - lod->rate;
  else if (measured && ms < 0.85 * lod->budget_ms) gpu.lod_near_m *= 1.0f + lod->rate;
  gpu.lod_near_m = std::clamp(gpu.lod_near_m, lo, hi);
  return gpu.lod_near_m;
}

// The layers the mesh clusters and the billboards draw are handed over to them: the clusters from
// their near_m (or the budget's distance) to their far_m, the billboards from there (or from their
// own near_m without clusters on the layer) to their far_m, beyond which the march resumes. Each
// hand-over cross-fades: the march's density and the paths' add up to the field's.
void hand_over_layers(World& world, const SystemContext& sc, CloudsGpu& gpu, PackedLayers& layers) {
  gpu.clusters_layer = gpu.billboards_layer = -1;
  Registry& reg = world.registry();
  const Entity ce = reg.first<CloudClusters>(), be = reg.first<CloudBillboards>();
  const CloudClusters* clusters = ce.is_null() ? nullptr : reg.get<CloudClusters>(ce);
  const CloudBillboards* billboards = be.is_null() ? nullptr : reg.get<CloudBillboards>(be);
  if (clusters && !(clusters->clusters > 0 && clusters->puffs_per_cluster > 0)) clusters = nullptr;
  if (billboards && !(billboards->billboards > 0)) billboards = nullptr;
  const float near_m = clusters ? handover_distance(world, sc, *clusters, gpu) : 0.0f;
  for (size_t i = 0; i < layers.layers.size(); ++i) {
    const int source = layers.source_index[i];
    const bool clustered = clusters && source == clusters->layer;
    const bool far = billboards && source == billboards->layer;
    if (clustered) {
      gpu.clusters_layer = int(i);
      gpu.clusters_near_m = near_m;
      layers.layers[i].handover = {std::max(near_m, 1e-3f), clusters->crossfade_m, clusters->far_m, 0.0f};
    }
    if (far) {
      gpu.billboards_layer = int(i);
      const float end = billboards->far_m;
      if (clustered) {
        // In where the puffs fade out (the last cross-fade before their far_m), out as the march
        // comes back: over the clusters' cross-fade, the one width the layer's hand-over has.
        const float w = clusters->crossfade_m;
        gpu.billboards_fade = {clusters->far_m - w, clusters->far_m, std::max(end - w, clusters->far_m), std::max(end, clusters->far_m + 1.0f)};
        layers.layers[i].handover.z = gpu.billboards_fade.w;
      } else {
        const float w = billboards->crossfade_m;
        gpu.billboards_fade = {billboards->near_m - 0.5f * w, billboards->near_m + 0.5f * w, end - w, end};
        layers.layers[i].handover = {std::max(billboards->near_m, 1e-3f), w, end, 0.0f};
      }
    }
  }
}

bool camera_in_space(World& world, const FrameBlock& f) {
  auto top = scene_scalar(world, "atmosphere.Atmosphere", "top_radius_km");
  return top && double(f.planet.z) > *top * 1000.0;
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
  if (!layers.layers.empty()) gpu.layer_buffer->upload(layers.layers.data(), layers.layers.size() * sizeof(LayerBlock));
  gpu.layers = layers.layers;

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
    key.settings.insert(key.settings.end(), {b.altitude.x, b.altitude.y, b.altitude.z, b.altitude.w, b.shape.x, b.shape.y,
                                             b.shape.z, b.shape.w, b.profile.x, b.profile.y, b.profile.z, b.profile.w,
                                             b.model.x, b.model.y, b.model.z, b.model.w});
  }
  for (const CloudLayer& L : clouds.layers) key.max_wind_mps = std::max(key.max_wind_mps, glm::length(L.wind_mps));
  key.settings.insert(key.settings.end(), {block.medium.x, block.medium.y, float(clouds.seed), clouds.shape_period_m,
                                           clouds.weather_period_m, clouds.shadow_distance_m, float(cascades), block.map_up.w,
                                           float(ctx.coverage_map_revision & 0xffffffu), clouds.coverage_map_size_m,
                                           clouds.weather_system_amount, clouds.weather_system_period_m});
  // Cascade k (0 nearest) covers a square of side 2 D / 4^(n - 1 - k) around the camera; each is
  // remade on its own, when it is stale at its own texel size (the nearest follows the camera most).
  const glm::vec3 u = glm::normalize(glm::cross(l, std::abs(l.z) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1)));
  const glm::vec3 v = glm::cross(l, u);
  const float start = std::max((layers.highest_shadow_m - block.planet.y) / std::max(l.z, 0.05f), 0.0f) + 100.0f;
  for (int k = 0; k < kMaxShadowCascades; ++k) {
    ShadowKey& held = gpu.shadow_keys[k];
    gpu.shadow_rebuild[k] = false;
    if (!key.wanted || k >= cascades) {
      held.wanted = false;
      gpu.shadow.origin[k].w = 0.0f;
      continue;
    }
    const float side = 2.0f * clouds.shadow_distance_m / float(1 << (2 * (cascades - 1 - k)));
    ShadowKey cascade = key;
    cascade.texel_m = side / float(clouds.shadow_map_size);
    gpu.shadow_rebuild[k] = !held.wanted || held.stale(cascade);
    if (gpu.shadow_rebuild[k]) {
      gpu.shadow.axis_u[k] = glm::vec4(u / side, start);
      gpu.shadow.axis_v[k] = glm::vec4(v / side, side);
      held = cascade;
    }
    // A cascade stays where it was made: its centre, relative to this frame's camera.
    gpu.shadow.origin[k] = glm::vec4(glm::vec3(held.anchor_m - view.camera_position_m), 1.0f);
  }
  gpu.shadow.light = glm::vec4(l, std::abs(l.z));
  gpu.shadow.up = glm::vec4(glm::vec3(block.up), float(key.wanted ? cascades : 0));
  return !layers.layers.empty();
}

}  // namespace

namespace {

// Bump when the C++ that finishes the volumes (equalise, pack_turbulence, void_and_cluster) changes:
// the cache's key holds the shaders' sources, not this code.
constexpr int kNoiseCacheVersion = 1;

// Level 0 of each volume, 8-bit, as the march reads it, and the blue noise: what the disk cache holds.
struct NoiseBytes {
  std::vector<uint8_t> shape, detail, weather, systems;
  std::vector<float> blue;
};
constexpr size_t kShapeBytes = size_t(kShapeNoiseSize) * kShapeNoiseSize * kShapeNoiseSize * 4;
constexpr size_t kDetailBytes = size_t(kDetailNoiseSize) * kDetailNoiseSize * kDetailNoiseSize;
constexpr size_t kWeatherBytes = size_t(kWeatherNoiseSize) * kWeatherNoiseSize * kWeatherNoiseSize * 4;
constexpr size_t kSystemsBytes = size_t(kSystemsNoiseSize) * kSystemsNoiseSize * kSystemsNoiseSize;
constexpr size_t kBlueBytes = size_t(kBlueNoiseSize) * kBlueNoiseSize * sizeof(float);

// The noise is a pure function of the seed, the sizes, the generating shaders, this code's version
// and the GL implementation that runs them: all of it is the disk cache's key.
std::string noise_key(const ShaderLibrary& shaders, int seed) {
  std::string key = "welkin clouds: noise volumes, version " + std::to_string(kNoiseCacheVersion) + ", seed " +
                    std::to_string(seed) + ", sizes " + std::to_string(kShapeNoiseSize) + " " + std::to_string(kDetailNoiseSize) +
                    " " + std::to_string(kWeatherNoiseSize) + " " + std::to_string(kSystemsNoiseSize) + " " +
                    std::to_string(kBlueNoiseSize) + "\n";
  key += current_gl_info().key();
  for (const char* kind : {"0", "1", "2", "3", "4"}) key += shaders.preprocess("clouds/noise.comp", {{"CLOUDS_NOISE", kind}}).text;
  return key;
}

std::optional<NoiseBytes> load_noise(const DiskCache& cache, const std::string& key) {
  auto bytes = cache.read(key, kShapeBytes + kDetailBytes + kWeatherBytes + kSystemsBytes + kBlueBytes);
  if (!bytes) return std::nullopt;
  NoiseBytes n;
  auto at = bytes->begin();
  for (auto [v, size] : {std::pair{&n.shape, kShapeBytes}, {&n.detail, kDetailBytes}, {&n.weather, kWeatherBytes}, {&n.systems, kSystemsBytes}}) {
    v->assign(at, at + std::ptrdiff_t(size));
    at += std::ptrdiff_t(size);
  }
  n.blue.resize(size_t(kBlueNoiseSize) * kBlueNoiseSize);
  std::memcpy(n.blue.data(), &*at, kBlueBytes);
  return n;
}

void store_noise(const DiskCache& cache, const std::string& key, const NoiseBytes& n) {
  std::string bytes;
  for (const auto* v : {&n.shape, &n.detail, &n.weather, &n.systems}) bytes.append(v->begin(), v->end());
  bytes.append(reinterpret_cast<const char*>(n.blue.data()), kBlueBytes);
  cache.write(key, bytes);
}

// Generates the volumes on the GPU and finishes them (equalised, the curl packed into the shape).
NoiseBytes generate_noise(RenderContext& rc, CloudsGpu& gpu, int seed) {
  // The curl field at the shape's size, packed into its gba below.
  Texture curl({.width = kShapeNoiseSize, .height = kShapeNoiseSize, .depth = kShapeNoiseSize, .format = TextureFormat::rgba16f});
  const std::pair<Texture*, const char*> volumes[] = {
      {gpu.shape.get(), "0"}, {gpu.detail.get(), "1"}, {gpu.weather.get(), "2"}, {&curl, "3"}, {gpu.systems.get(), "4"}};
  for (auto [texture, kind] : volumes) {
    const Program& p = rc.shaders.compute("clouds/noise.comp", {{"CLOUDS_NOISE", kind}});
    p.set("u_size", texture->desc().width);
    glProgramUniform1ui(p.id(), p.location("u_seed"), GLuint(seed));
    bind_image_for_write(0, *texture);
    const int g = group_count(texture->desc().width, 4);
    dispatch_compute(p, g, g, g);
  }
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  NoiseBytes n;
  n.weather = equalise(*gpu.weather, GL_RGBA, 4, 3);
  n.shape = pack_turbulence(*gpu.shape, curl);
  n.systems = equalise(*gpu.systems, GL_RED, 1, 1);
  n.detail = read_volume(*gpu.detail, GL_RED, kDetailBytes);
  n.blue = void_and_cluster(kBlueNoiseSize, uint32_t(seed));
  ++gpu.noise_builds;
  return n;
}

}  // namespace

void ensure_noise(World& world, int seed) {
  auto& gpu = world.resource<CloudsGpu>();
  if (gpu.noise_seed == seed) return;
  auto& rc = world.resource<RenderContext>();
  ensure_texture(gpu.shape, {.width = kShapeNoiseSize, .height = kShapeNoiseSize, .depth = kShapeNoiseSize,
                             .format = TextureFormat::rgba8, .clamp = false, .mipmaps = true});
  ensure_texture(gpu.detail, {.width = kDetailNoiseSize, .height = kDetailNoiseSize, .depth = kDetailNoiseSize,
                              .format = TextureFormat::r8, .clamp = false, .mipmaps = true});
  ensure_texture(gpu.weather, {.width = kWeatherNoiseSize, .height = kWeatherNoiseSize, .depth = kWeatherNoiseSize,
                               .format = TextureFormat::rgba8, .clamp = false, .mipmaps = true});
  ensure_texture(gpu.systems, {.width = kSystemsNoiseSize, .height = kSystemsNoiseSize, .depth = kSystemsNoiseSize,
                               .format = TextureFormat::r8, .clamp = false, .mipmaps = true});
  // Made before, by this program on this GL: read from the disk cache (on llvmpipe the generation is
  // most of a cloudy scene's start-up: 3.7 s of the default demo's 6.9).
  const DiskCache cache = DiskCache::from_environment();
  const std::string key = cache.enabled() ? noise_key(rc.shaders, seed) : std::string();
  std::optional<NoiseBytes> noise = cache.enabled() ? load_noise(cache, key) : std::nullopt;
  if (noise) {
    upload_volume(*gpu.shape, GL_RGBA, noise->shape);
    upload_volume(*gpu.detail, GL_RED, noise->detail);
    upload_volume(*gpu.weather, GL_RGBA, noise->weather);
    upload_volume(*gpu.systems, GL_RED, noise->systems);
    ++gpu.noise_cache_reads;
  } else {
    noise = generate_noise(rc, gpu, seed);
    if (cache.enabled()) store_noise(cache, key, *noise);
  }
  gpu.noise_facts = systems_facts(noise->systems, kSystemsNoiseSize);
  ensure_texture(gpu.weather_maximum, {.width = kWeatherOccupancySize, .height = kWeatherOccupancySize, .depth = kWeatherOccupancySize,
                                       .format = TextureFormat::rgba8, .linear_filter = false, .clamp = false});
  glTextureSubImage3D(gpu.weather_maximum->id(), 0, 0, 0, 0, kWeatherOccupancySize, kWeatherOccupancySize, kWeatherOccupancySize,
                      GL_RGBA, GL_UNSIGNED_BYTE, weather_maximum(noise->weather, kWeatherNoiseSize).data());
  // Far away a pixel spans many texels: the march reads coarser levels there instead of aliasing.
  // Between levels the nearer one is read, not a blend of two: a 3D trilinear read costs 16 texels
  // (twice a bilinear one), and on software rasterisers the march's texture reads are most of its cost.
  for (Texture* t : {gpu.shape.get(), gpu.detail.get(), gpu.weather.get(), gpu.systems.get()}) {
    glGenerateTextureMipmap(t->id());
    glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
  }
  ensure_texture(gpu.blue_noise, {.width = kBlueNoiseSize, .height = kBlueNoiseSize, .format = TextureFormat::r32f,
                                  .linear_filter = false, .clamp = false});
  glTextureSubImage2D(gpu.blue_noise->id(), 0, 0, 0, kBlueNoiseSize, kBlueNoiseSize, GL_RED, GL_FLOAT, noise->blue.data());
  gpu.noise_seed = seed;
}

void add_light_term(World& world) {
  world.resource<LightEnvironment>().add(LightTerm{
      .name = "clouds.shadows",
      .include = "clouds/light_term.glsl",
      .light_visibility = "clouds_light_visibility",
      .sky_visibility = "clouds_sky_visibility",
      .added_irradiance = "clouds_added_irradiance",
      .surface_light = "clouds_surface_light",
      .textures = {"clouds.shadow_map"},
      .blocks = {"clouds.shadow"},
      .bind = [&world](const LightEnvironment& env) {
        CloudsGpu& gpu = world.resource<CloudsGpu>();
        ShadowBlock s = gpu.shadow;
        if (!gpu.shadow_map) s.up.w = 0.0f;
        env.bind_block("clouds.shadow", gpu.shadow_buffer, &s, sizeof(s));
        if (gpu.shadow_map) glBindTextureUnit(env.unit("clouds.shadow_map"), gpu.shadow_map->id());
      },
      // The block, the cascades remade so far and those this frame remakes.
      .state = [&world] {
        const CloudsGpu& gpu = world.resource<CloudsGpu>();
        return fnv1a_64_of(gpu.shadow, fnv1a_64_of(gpu.shadow_builds, fnv1a_64_of(gpu.shadow_rebuild,
                                                                                   fnv1a_64_of(uintptr_t(gpu.shadow_map.get())))));
      }});
}

// Before the geometry: noise, this frame's block, and the shadow map every material reads.
void shadow_system(SystemContext& sc) {
  World& world = sc.world;
  const VolumetricClouds* clouds = first_clouds(world);
  if (!clouds) return;
  auto& gpu = world.resource<CloudsGpu>();
  ensure_noise(world, clouds->seed);
  gpu.has_layers = upload_frame(world, sc, *clouds, gpu.block);
  if (!gpu.has_layers || gpu.shadow.up.w < 0.5f) {
    gpu.shadow.up.w = 0.0f;
    for (ShadowKey& k : gpu.shadow_keys) k.wanted = false;
    return;
  }
  const int cascades = int(gpu.shadow.up.w), size = clouds->shadow_map_size;
  // The cascades side by side in one texture, nearest first; a new texture holds none of them yet.
  if (ensure_texture(gpu.shadow_map, {.width = size * cascades, .height = size, .format = TextureFormat::rgba32f}))
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
      [gp, &rc, s, remade, size, defines = field_defines(gpu)](PassContext&) {
        bind_field(*gp);
        bind_image_for_write(0, *gp->shadow_map);
        const Program& p = rc.shaders.compute("clouds/shadow_map.comp", defines);
        for (int k : remade) {
          const float side = s.axis_v[k].w;
          // The plane through the cascade's centre (camera-relative, this frame).
          p.set("u_centre", glm::vec3(s.origin[k]));
          p.set("u_light", glm::vec3(s.light));
          p.set("u_axis_u", glm::vec3(s.axis_u[k]) * side);
          p.set("u_axis_v", glm::vec3(s.axis_v[k]) * side);
          p.set("u_extent_m", side);
          p.set("u_start_m", s.axis_u[k].w);
          p.set("u_steps", kShadowSteps);
          glProgramUniform2i(p.id(), p.location("u_region"), k * size, size);
          const int g = group_count(size, 8);
          dispatch_compute(p, g, g);
          ++gp->shadow_builds;
        }
      });
}

static void composite_clouds(RenderGraph& g, RenderContext& rc, const FrameTargets& t, ResourceHandle result,
                             ResourceHandle clusters);

// After the geometry and its aerial perspective: the march and the composite.
void clouds_system(SystemContext& sc) {
  World& world = sc.world;
  const VolumetricClouds* clouds = first_clouds(world);
  if (!clouds) return;
  auto& gpu = world.resource<CloudsGpu>();
  auto& rc = world.resource<RenderContext>();
  // No layer holds cloud (coverage 0, no thickness or density): nothing is marched.
  if (!gpu.has_layers) return;
  const int w = int(gpu.block.frame.z), h = int(gpu.block.frame.w);
  const FrameView& view = rc.view;
  const char* ap_mode = camera_in_space(world, gpu.block) ? "2" : clouds->aerial_perspective == CloudAerialPerspective::mean_depth ? "1" : "0";
  // The field's layers and what each uses are compiled in, turbulence only where it displaces anything.
  ShaderDefines defines = field_defines(gpu);
  defines.merge(light_model_defines(gpu));
  defines["CLOUDS_AP_MODE"] = ap_mode;
  // The mesh clusters drawn just before: the march ends where they turn opaque.
  // (published on the graph's blackboard by clouds.clusters when it drew this frame).
  const auto published = [&sc](const char* name) {
    auto it = sc.graph->blackboard.find(name);
    return it == sc.graph->blackboard.end() ? ResourceHandle{} : it->second;
  };
  const ResourceHandle front = published("clouds.cluster_front");
  const bool cluster_front = front.valid();
  const GLuint front_unit = world.resource<LightEnvironment>().free_unit();
  if (cluster_front) {
    defines["CLOUDS_CLUSTER_FRONT"] = "1";
    defines["CLOUDS_UNIT_CLUSTER_FRONT"] = std::to_string(front_unit);
  }
  // A frame rendered alone marches every pixel (the history is another moment's).
  const bool temporal = clouds->temporal_upscaling && !sc.frame.alone && w >= 2 && h >= 2;
  if (temporal) {
    ensure_texture(gpu.history_color[gpu.history_index], {.width = w, .height = h, .format = TextureFormat::rgba16f});
    if (!gpu.history_color[1 - gpu.history_index]) {
      ensure_texture(gpu.history_color[1 - gpu.history_index], {.width = w, .height = h, .format = TextureFormat::rgba16f});
      gpu.history_valid = false;
    }
  }
  // Without a history (the first frame, a new size, after a frame without upscaling) every pixel is
  // marched once and becomes the history; then one pixel of each block per frame, in the order of a
  // Bayer matrix (each next pixel as far as it can be from those marched just before).
  const bool partial = temporal && gpu.history_valid;
  const int n = partial ? resolve_quality(*clouds).temporal_block : 1;
  const FrameTargets t = *sc.targets;
  RenderGraph& g = *sc.graph;
  ResourceHandle clusters = published("clouds.clusters");

  // What the march and the resolve read, the frame's index aside (it only turns the jitter): the
  // block and layers, the field's noise and map, the shaders, the light environment's state, the
  // geometry's. Clusters and billboards drawn before the march are not followed: with them it marches.
  const std::optional<uint64_t> light = world.resource<LightEnvironment>().state();
  if (partial && light && !clusters.valid()) {
    FrameBlock block = gpu.block;
    block.frame.x = 0.0f;
    uint64_t state = fnv1a_64_of(block, fnv1a_64_of(*light, fnv1a_64_of(t.geometry_state)));
    state = fnv1a_64(std::string_view(reinterpret_cast<const char*>(gpu.layers.data()), gpu.layers.size() * sizeof(LayerBlock)), state);
    const int field[6] = {gpu.noise_seed, gpu.noise_builds, gpu.noise_cache_reads, n, w, h};
    state = fnv1a_64_of(gpu.coverage_map_revision, fnv1a_64_of(field, state));
    state = fnv1a_64(gpu.coverage_map_file, state);
    for (const auto& [k, v] : defines) state = fnv1a_64(k + "=" + v + ";", state);
    if (state != gpu.march_state) gpu.march_state = state, gpu.march_state_frames = 0;
  } else {
    gpu.march_state_frames = 0, gpu.march_state = 0;
  }
  if (partial && gpu.march_state != 0 && gpu.march_state_frames >= n * n) {
    // Kept: the history as the last frame's resolve left it.
    const ResourceHandle kept = g.import("clouds.history_color", *gpu.history_color[1 - gpu.history_index]);
    composite_clouds(g, rc, t, kept, {});
    gpu.previous_view_projection = view.view_projection;
    gpu.previous_camera_m = view.camera_position_m;
    return;
  }
  if (gpu.march_state != 0) ++gpu.march_state_frames;
  ++gpu.marches;
  if (!partial) ++gpu.full_marches;

  const int qw = (w + n - 1) / n, qh = (h + n - 1) / n;
  static constexpr glm::ivec2 kOffsets2[4] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  static constexpr glm::ivec2 kOffsets4[16] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                               {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};
  const glm::ivec2 offset = !partial ? glm::ivec2(0)
                            : n == 4 ? kOffsets4[gpu.temporal_frame++ % 16]
                                     : kOffsets2[gpu.temporal_frame++ % 4];
  const glm::ivec3 stride_offset(n, offset.x, offset.y);

  auto current = std::make_shared<std::array<ResourceHandle, 2>>();
  CloudsGpu* gp = &gpu;
  g.add_pass(
      "clouds.march",
      [&](PassBuilder& b) {
        b.read(t.depth);
        if (cluster_front) b.read(front);
        (*current)[0] = b.create("clouds.march", TextureDesc{.width = qw, .height = qh, .format = TextureFormat::rgba16f});
        (*current)[1] = b.create("clouds.march_distance",
                                 TextureDesc{.width = qw, .height = qh, .format = TextureFormat::rg32f, .linear_filter = false});
      },
      [gp, &rc, &world, t, current, defines, stride_offset, cluster_front, front, front_unit](PassContext& pc) {
        Framebuffer fb({&pc.texture((*current)[0]), &pc.texture((*current)[1])}, nullptr);
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        // GL forbids several draw buffers while the blend function names a second source colour
        // (the atmosphere's aerial perspective leaves one), even with blending off.
        glBlendFunc(GL_ONE, GL_ZERO);
        world.resource<LightEnvironment>().bind();
        bind_field(*gp);
        glBindTextureUnit(3, pc.texture(t.depth).id());
        glBindTextureUnit(4, gp->blue_noise->id());
        if (cluster_front) glBindTextureUnit(front_unit, pc.texture(front).id());
        const Program& p = rc.shaders.graphics("fullscreen.vert", "clouds/march.frag", defines);
        p.use();
        glProgramUniform3i(p.id(), p.location("u_stride_offset"), stride_offset.x, stride_offset.y, stride_offset.z);
        rc.draw_fullscreen_triangle();
      });

  ResourceHandle result = (*current)[0];
  // The mesh clusters (and billboards) drawn before the march lie behind it. At the march's resolution
  // the resolve lays them in as it writes (a read at a quarter of the frame's pixels); otherwise the
  // composite reads them at the frame's resolution.
  const bool merge_clusters = temporal && clusters.valid() && sc.graph->resource_desc(clusters).width == w &&
                              sc.graph->resource_desc(clusters).height == h;
  if (temporal) {
    const int write = gpu.history_index, read = 1 - write;
    const ResourceHandle out_color = g.import("clouds.history_color", *gpu.history_color[write]);
    const ResourceHandle history = g.import("clouds.history_previous", *gpu.history_color[read]);
    const glm::vec3 moved = glm::vec3(view.camera_position_m - gpu.previous_camera_m);
    const glm::mat4 previous_vp = gpu.previous_view_projection, inverse_vp = view.inverse_view_projection;
    const bool valid = gpu.history_valid;
    const float inside_cloud_m = 2.0f * gpu.block.steps.y;  // two of the shortest march steps
    const ShaderDefines resolve_defines = {{"CLOUDS_CLIP", clouds->temporal_clipping ? "1" : "0"},
                                           {"CLOUDS_WITH_CLUSTERS", merge_clusters ? "1" : "0"}};
    auto merged = std::make_shared<ResourceHandle>();
    g.add_pass(
        "clouds.resolve",
        [&](PassBuilder& b) {
          b.read((*current)[0]);
          b.read((*current)[1]);
          b.read(history);
          b.write(out_color);
          if (merge_clusters) {
            b.read(clusters);
            *merged = b.create("clouds.with_clusters", TextureDesc{.width = w, .height = h, .format = TextureFormat::rgba16f});
          }
        },
        [&rc, current, out_color, history, offset, moved, previous_vp, inverse_vp, valid,
         resolve_defines, inside_cloud_m, partial, n, merge_clusters, clusters, merged](PassContext& pc) {
          Framebuffer fb = merge_clusters ? Framebuffer({&pc.texture(out_color), &pc.texture(*merged)}, nullptr)
                                          : Framebuffer(&pc.texture(out_color), nullptr);
          fb.bind();
          glDisable(GL_DEPTH_TEST);
          glDisable(GL_BLEND);
          glBlendFunc(GL_ONE, GL_ZERO);  // no second source colour while several buffers are drawn
          glBindTextureUnit(0, pc.texture((*current)[0]).id());
          glBindTextureUnit(1, pc.texture((*current)[1]).id());
          glBindTextureUnit(2, pc.texture(history).id());
          if (merge_clusters) glBindTextureUnit(3, pc.texture(clusters).id());
          const Program& p = rc.shaders.graphics("fullscreen.vert", "clouds/resolve.frag", resolve_defines);
          p.use();
          glProgramUniform2i(p.id(), p.location("u_offset"), offset.x, offset.y);
          glProgramUniform1i(p.id(), p.location("u_block"), n);
          p.set("u_inverse_view_projection", inverse_vp);
          p.set("u_previous_view_projection", previous_vp);
          p.set("u_camera_moved_m", moved);
          p.set("u_history_valid", valid ? 1 : 0);
          p.set("u_full_frame", partial ? 0 : 1);
          p.set("u_inside_cloud_m", inside_cloud_m);
          rc.draw_fullscreen_triangle();
        });
    result = merge_clusters ? *merged : out_color;
    if (merge_clusters) clusters = {};
    gpu.history_index = read;
    gpu.history_valid = true;
  } else {
    gpu.history_valid = false;
  }
  gpu.previous_view_projection = view.view_projection;
  gpu.previous_camera_m = view.camera_position_m;
  composite_clouds(g, rc, t, result, clusters);
}

// The clouds (and the clusters or billboards behind them, where not merged already) over the frame.
static void composite_clouds(RenderGraph& g, RenderContext& rc, const FrameTargets& t, ResourceHandle result,
                             ResourceHandle clusters) {
  g.add_pass(
      "clouds.composite",
      [&](PassBuilder& b) {
        b.read(result);
        if (clusters.valid()) b.read(clusters);
        b.read(t.color);
        b.write(t.color);
      },
      [&rc, t, result, clusters](PassContext& pc) {
        Framebuffer fb(&pc.texture(t.color), nullptr);
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_SRC_ALPHA);  // clouds + transmittance x what lies behind
        glBindTextureUnit(0, pc.texture(result).id());
        if (clusters.valid()) glBindTextureUnit(1, pc.texture(clusters).id());
        const Program& p = rc.shaders.graphics("fullscreen.vert", "clouds/composite.frag",
                                               {{"CLOUDS_WITH_CLUSTERS", clusters.valid() ? "1" : "0"}});
        p.use();
        rc.draw_fullscreen_triangle();
        glDisable(GL_BLEND);
      });
}

}  // namespace welkin::clouds
