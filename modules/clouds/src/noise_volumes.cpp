// The noise volumes the density field reads, generated on the GPU once per seed and finished on the
// CPU (equalised, the curl field packed into the shape), or read from the disk cache (noise_cache.h).
#include "noise_volumes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "clouds_gpu.h"
#include "noise_cache.h"
#include "weather_levels.h"
#include "welkin/clouds/blue_noise.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

namespace {

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
  glTextureSubImage3D(volume.id(), 0, 0, 0, 0, d.width, d.height, d.depth, format, GL_UNSIGNED_BYTE,
                      data.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

// Levels 1 and up of a cube 8-bit volume with `channels` bytes a texel, tightly packed in order: read
// back once made (glGenerateTextureMipmap), uploaded when read from the disk cache. Making them again
// costs a blit per slice and level, and on llvmpipe compiling the blits each start: in the demo's warm
// start-up, 0.16 s of the 0.21 s that LLVM took on the main thread.
void read_mips(const Texture& volume, GLenum format, int channels, std::vector<uint8_t>& out) {
  const size_t at = out.size();
  out.resize(at + mip_bytes(volume.desc().width, channels));
  uint8_t* p = out.data() + at;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int level = 1, s = volume.desc().width / 2; s >= 1; ++level, s /= 2) {
    const size_t bytes = size_t(s) * size_t(s) * size_t(s) * size_t(channels);
    glGetTextureImage(volume.id(), level, format, GL_UNSIGNED_BYTE, GLsizei(bytes), p);
    p += bytes;
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
}
const uint8_t* upload_mips(Texture& volume, GLenum format, int channels, const uint8_t* p) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int level = 1, s = volume.desc().width / 2; s >= 1; ++level, s /= 2) {
    glTextureSubImage3D(volume.id(), level, 0, 0, 0, s, s, s, format, GL_UNSIGNED_BYTE, p);
    p += size_t(s) * size_t(s) * size_t(s) * size_t(channels);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return p;
}

// Equalises the first `channels_equalised` channels of an 8-bit volume (GL_RGBA: 4 channels, GL_RED: 1)
// to a uniform distribution, so that a layer's coverage c covers a fraction c of the sky whatever the
// noise's own histogram.
std::vector<uint8_t> equalise(Texture& volume, GLenum format, int channels, int channels_equalised) {
  const size_t n = size_t(volume.desc().width) * size_t(volume.desc().height) * size_t(volume.desc().depth);
  std::vector<uint8_t> data = read_volume(volume, format, n * size_t(channels));
  std::vector<uint32_t> keys(n);
  for (size_t c = 0; c < size_t(channels_equalised); ++c) {
    for (size_t i = 0; i < n; ++i) keys[i] = data[i * size_t(channels) + c];
    const std::vector<uint8_t> v = equalised(keys);
    for (size_t i = 0; i < n; ++i) data[i * size_t(channels) + c] = v[i];
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
      texels[i * 4 + 1 + a] =
          uint8_t(std::lround(std::clamp(127.5 + 127.5 * c[i * 4 + a] / longest, 0.0, 255.0)));
  upload_volume(shape, GL_RGBA, texels);
  return texels;
}

// What the weather systems need of their (equalised, R8) volume: the largest step
// between neighbouring texels (across the wrap too), and the anchor: of the texels nearest the
// median (equalisation may skip levels), the one whose neighbourhood is flattest, so that the scene's
// origin and its surroundings keep their layers' own coverage.
NoiseFacts systems_facts(const std::vector<uint8_t>& v, int size) {
  auto at = [&](int x, int y, int z) {
    return int(
        v[(size_t((z + size) % size) * size + size_t((y + size) % size)) * size + size_t((x + size) % size)]);
  };
  NoiseFacts facts;
  int largest = 0;
  std::pair<int, int> best{1 << 30, 0};  // distance from the median (in half levels), spread
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const int v0 = at(x, y, z);
        const int dx = std::abs(at(x + 1, y, z) - v0), dy = std::abs(at(x, y + 1, z) - v0),
                  dz = std::abs(at(x, y, z + 1) - v0);
        largest = std::max({largest, dx, dy, dz});
        const int spread = dx + dy + dz + std::abs(at(x - 1, y, z) - v0) + std::abs(at(x, y - 1, z) - v0) +
                           std::abs(at(x, y, z - 1) - v0);
        const std::pair<int, int> score{std::abs(2 * v0 - 255), spread};
        if (score < best) best = score, facts.system_anchor = (glm::vec3(x, y, z) + 0.5f) / float(size);
      }
  facts.weather_step = float(largest) / 255.0f;
  return facts;
}

// Generates the volumes on the GPU and finishes them (equalised, the curl packed into the shape).
NoiseBytes generate_noise(RenderContext& rc, CloudsGpu& gpu, int seed) {
  // The curl field at the shape's size, packed into its gba below.
  Texture curl({.width = kShapeNoiseSize,
                .height = kShapeNoiseSize,
                .depth = kShapeNoiseSize,
                .format = TextureFormat::rgba16f});
  const std::pair<Texture*, const char*> volumes[] = {{gpu.shape.get(), "0"},
                                                      {gpu.detail.get(), "1"},
                                                      {gpu.weather.get(), "2"},
                                                      {&curl, "3"},
                                                      {gpu.systems.get(), "4"}};
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
  n.weather = equalise(*gpu.weather, GL_RGBA, 4, kWeatherEqualisedChannels);
  // The shape noise too (its Perlin-Worley values crowd between 0.69 and 0.86): spread evenly, its
  // erosion reaches every depth of a cloud and draws the edges, where the weather's slow ramp did.
  equalise(*gpu.shape, GL_RGBA, 4, 1);
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
  ensure_texture(gpu.shape, {.width = kShapeNoiseSize,
                             .height = kShapeNoiseSize,
                             .depth = kShapeNoiseSize,
                             .format = TextureFormat::rgba8,
                             .clamp = false,
                             .mipmaps = true});
  ensure_texture(gpu.detail, {.width = kDetailNoiseSize,
                              .height = kDetailNoiseSize,
                              .depth = kDetailNoiseSize,
                              .format = TextureFormat::r8,
                              .clamp = false,
                              .mipmaps = true});
  ensure_texture(gpu.weather, {.width = kWeatherNoiseSize,
                               .height = kWeatherNoiseSize,
                               .depth = kWeatherNoiseSize,
                               .format = TextureFormat::rgba8,
                               .clamp = false,
                               .mipmaps = true});
  ensure_texture(gpu.systems, {.width = kSystemsNoiseSize,
                               .height = kSystemsNoiseSize,
                               .depth = kSystemsNoiseSize,
                               .format = TextureFormat::r8,
                               .clamp = false,
                               .mipmaps = true});
  // Made before, by this program on this GL: read from the disk cache (on llvmpipe the generation is
  // most of a cloudy scene's start-up: 3.7 s of the default demo's 6.9).
  const DiskCache cache = DiskCache::from_environment();
  const std::string key = cache.enabled() ? noise_key(rc.shaders, seed) : std::string();
  std::optional<NoiseBytes> noise = cache.enabled() ? load_noise(cache, key) : std::nullopt;
  // Far away a pixel spans many texels: the march reads coarser levels there instead of aliasing.
  const std::tuple<Texture*, GLenum, int> volumes[] = {{gpu.shape.get(), GL_RGBA, 4},
                                                       {gpu.detail.get(), GL_RED, 1},
                                                       {gpu.weather.get(), GL_RGBA, 4},
                                                       {gpu.systems.get(), GL_RED, 1}};
  if (noise) {
    upload_volume(*gpu.shape, GL_RGBA, noise->shape);
    upload_volume(*gpu.detail, GL_RED, noise->detail);
    upload_volume(*gpu.weather, GL_RGBA, noise->weather);
    upload_volume(*gpu.systems, GL_RED, noise->systems);
    const uint8_t* mips = noise->mips.data();
    for (auto [t, format, channels] : volumes) mips = upload_mips(*t, format, channels, mips);
    ++gpu.noise_cache_reads;
  } else {
    noise = generate_noise(rc, gpu, seed);
    for (auto [t, format, channels] : volumes) {
      // The weather's levels are equalised (weather_levels.h), the others' averages.
      if (t == gpu.weather.get())
        upload_mips(*t, format, channels, weather_levels(noise->weather, kWeatherNoiseSize).data());
      else
        glGenerateTextureMipmap(t->id());
      if (cache.enabled()) read_mips(*t, format, channels, noise->mips);
    }
    if (cache.enabled()) store_noise(cache, key, *noise);
  }
  gpu.noise_facts = systems_facts(noise->systems, kSystemsNoiseSize);
  ensure_texture(gpu.weather_maximum, {.width = kWeatherOccupancySize,
                                       .height = kWeatherOccupancySize,
                                       .depth = kWeatherOccupancySize * kWeatherLevels,
                                       .format = TextureFormat::rgba8,
                                       .linear_filter = false,
                                       .clamp = false});
  std::vector<uint8_t> weather_mips;
  read_mips(*gpu.weather, GL_RGBA, 4, weather_mips);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(gpu.weather_maximum->id(), 0, 0, 0, 0, kWeatherOccupancySize, kWeatherOccupancySize,
                      kWeatherOccupancySize * kWeatherLevels, GL_RGBA, GL_UNSIGNED_BYTE,
                      weather_occupancy(noise->weather, weather_mips, kWeatherNoiseSize).data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  // Between levels the nearer one is read, not a blend of two: a 3D trilinear read costs 16 texels
  // (twice a bilinear one), and on software rasterisers the march's texture reads are most of its cost.
  // Not the weather's: its levels are equalised (weather_levels.h), so two levels differ in where
  // their clouds are, not only in how thin, and the nearer level swaps one set for the other at a
  // distance. Blended, a turning view at half size is 7.3% off a full march (7.9% with the nearer
  // level; CloudsGpu.AViewThatStartsOrStopsMovingKeepsItsHistory) for 1.7% more march time on llvmpipe.
  for (auto [t, format, channels] : volumes)
    glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER,
                        t == gpu.weather.get() ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST);
  ensure_texture(gpu.blue_noise, {.width = kBlueNoiseSize,
                                  .height = kBlueNoiseSize,
                                  .format = TextureFormat::r32f,
                                  .linear_filter = false,
                                  .clamp = false});
  glTextureSubImage2D(gpu.blue_noise->id(), 0, 0, 0, kBlueNoiseSize, kBlueNoiseSize, GL_RED, GL_FLOAT,
                      noise->blue.data());
  gpu.noise_seed = seed;
}

}  // namespace welkin::clouds
