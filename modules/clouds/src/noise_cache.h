#pragma once
// The noise volumes' disk cache: generating them is most of a cloudy scene's start-up on llvmpipe,
// and they are a pure function of what noise_key names.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "noise_volumes.h"
#include "welkin/core/disk_cache.h"
#include "welkin/gfx/shader.h"

namespace welkin::clouds {

// Each volume's bytes as the cache holds them.
inline constexpr size_t kShapeBytes = size_t(kShapeNoiseSize) * kShapeNoiseSize * kShapeNoiseSize * 4;
inline constexpr size_t kDetailBytes = size_t(kDetailNoiseSize) * kDetailNoiseSize * kDetailNoiseSize;
inline constexpr size_t kWeatherBytes = size_t(kWeatherNoiseSize) * kWeatherNoiseSize * kWeatherNoiseSize * 4;
inline constexpr size_t kSystemsBytes = size_t(kSystemsNoiseSize) * kSystemsNoiseSize * kSystemsNoiseSize;
inline constexpr size_t kBlueBytes = size_t(kBlueNoiseSize) * kBlueNoiseSize * sizeof(float);
// Levels 1 and up of a cube volume of side `size` with `channels` bytes a texel, tightly packed.
constexpr size_t mip_bytes(int size, int channels) {
  size_t bytes = 0;
  for (int s = size / 2; s >= 1; s /= 2) bytes += size_t(s) * size_t(s) * size_t(s) * size_t(channels);
  return bytes;
}
inline constexpr size_t kMipBytes = mip_bytes(kShapeNoiseSize, 4) + mip_bytes(kDetailNoiseSize, 1) +
                                    mip_bytes(kWeatherNoiseSize, 4) + mip_bytes(kSystemsNoiseSize, 1);

// Level 0 of each volume, 8-bit, as the march reads it, the blue noise, and the volumes' further
// levels (shape, detail, weather, systems in turn): what the disk cache holds.
struct NoiseBytes {
  std::vector<uint8_t> shape, detail, weather, systems;
  std::vector<float> blue;
  std::vector<uint8_t> mips;
};
// The noise is a pure function of the seed, the sizes, the generating shaders, this code's version
// and the GL implementation that runs them: all of it is the disk cache's key.
std::string noise_key(const ShaderLibrary& shaders, int seed);
std::optional<NoiseBytes> load_noise(const DiskCache& cache, const std::string& key);
void store_noise(const DiskCache& cache, const std::string& key, const NoiseBytes& n);

}  // namespace welkin::clouds
