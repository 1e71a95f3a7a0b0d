#pragma once
// The noise volumes the density field reads, generated on the GPU once per seed (noise_volumes.cpp).
#include <glm/glm.hpp>

namespace welkin {
class World;
}

namespace welkin::clouds {

// Noise volumes, generated on the GPU once per seed (sizes fixed by the module).
inline constexpr int kShapeNoiseSize = 128, kDetailNoiseSize = 32, kWeatherNoiseSize = 64,
                     kBlueNoiseSize = 64;
inline constexpr int kSystemsNoiseSize = 32;
inline constexpr int kWeatherOccupancySize = 16;  // blocks of 4^3 weather texels

// What the frame block needs of the generated noise.
struct NoiseFacts {
  glm::vec3 system_anchor{
      0.5f};  // a texel (uvw) of the systems' volume whose signal is 0.5: the scene's origin sits there
  float weather_step = 0.0f;  // the largest change of that signal between neighbouring texels
};

// Noise generation alone (also used by the CPU reference's field, which reads the volumes back).
void ensure_noise(World& world, int seed);

}  // namespace welkin::clouds
