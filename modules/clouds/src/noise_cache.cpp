// The noise volumes' disk cache (noise_cache.h).
#include "noise_cache.h"

#include <cstring>

#include "welkin/gfx/gl_context.h"

namespace welkin::clouds {

namespace {

// Bump when the C++ that finishes the volumes (equalise, weather_levels, pack_turbulence,
// void_and_cluster) changes: the cache's key holds the shaders' sources, not this code.
constexpr int kNoiseCacheVersion = 8;

}  // namespace

std::string noise_key(const ShaderLibrary& shaders, int seed) {
  std::string key = "welkin clouds: noise volumes, version " + std::to_string(kNoiseCacheVersion) +
                    ", seed " + std::to_string(seed) + ", sizes " + std::to_string(kShapeNoiseSize) + " " +
                    std::to_string(kDetailNoiseSize) + " " + std::to_string(kWeatherNoiseSize) + " " +
                    std::to_string(kSystemsNoiseSize) + " " + std::to_string(kBlueNoiseSize) + "\n";
  key += current_gl_info().key();
  for (const char* kind : {"0", "1", "2", "3", "4"})
    key += shaders.preprocess("clouds/noise.comp", {{"CLOUDS_NOISE", kind}}).text;
  return key;
}

std::optional<NoiseBytes> load_noise(const DiskCache& cache, const std::string& key) {
  auto bytes =
      cache.read(key, kShapeBytes + kDetailBytes + kWeatherBytes + kSystemsBytes + kBlueBytes + kMipBytes);
  if (!bytes) return std::nullopt;
  NoiseBytes n;
  auto at = bytes->begin();
  for (auto [v, size] : {std::pair{&n.shape, kShapeBytes},
                         {&n.detail, kDetailBytes},
                         {&n.weather, kWeatherBytes},
                         {&n.systems, kSystemsBytes}}) {
    v->assign(at, at + std::ptrdiff_t(size));
    at += std::ptrdiff_t(size);
  }
  n.blue.resize(size_t(kBlueNoiseSize) * kBlueNoiseSize);
  std::memcpy(n.blue.data(), &*at, kBlueBytes);
  at += std::ptrdiff_t(kBlueBytes);
  n.mips.assign(at, bytes->end());
  return n;
}

void store_noise(const DiskCache& cache, const std::string& key, const NoiseBytes& n) {
  std::string bytes;
  for (const auto* v : {&n.shape, &n.detail, &n.weather, &n.systems}) bytes.append(v->begin(), v->end());
  bytes.append(reinterpret_cast<const char*>(n.blue.data()), kBlueBytes);
  bytes.append(n.mips.begin(), n.mips.end());
  cache.write(key, bytes);
}

}  // namespace welkin::clouds
