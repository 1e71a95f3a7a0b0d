#pragma once
// The weather volume's coarser levels, each equalised as level 0 is, and the empty-space skip's
// occupancy over them (weather_levels.cpp).
#include <cstdint>
#include <vector>

#include "noise_volumes.h"

namespace welkin::clouds {

// The weather's r, g and b are the genera's coverage signals, which the layers threshold: each level
// of them is equalised. Its a, the base's variation, moves the base linearly: its levels are averages.
inline constexpr int kWeatherEqualisedChannels = 3;
// Levels 0 to 6 of the 64^3 weather.
inline constexpr int kWeatherLevels = 7;
static_assert(1 << (kWeatherLevels - 1) == kWeatherNoiseSize);

// Each key's mid-rank among all the keys, scaled to 0-255 (ties keep one value): a uniform
// distribution whatever the keys' own, in the keys' order.
std::vector<uint8_t> equalised(const std::vector<uint32_t>& keys);

// Levels 1 and up of the weather (RGBA8, a cube `size` texels a side, level 0 equalised), packed in
// order as the disk cache holds them: each texel the average of level 0 over it, the coverage channels
// then equalised by the ranks of those averages. Averages crowd toward the middle (a coverage of 0.3
// would cover almost nothing at level 3); equalised, a coverage c covers c of the sky at every level.
std::vector<uint8_t> weather_levels(const std::vector<uint8_t>& level0, int size);

// The coarse occupancy the march skips empty space with: for each block of (size / 16)^3 level-0
// texels and each level k, the largest signal of each coverage channel that a linear filter reads at
// a point in the block at any of the levels 0 to k (a coarser equalised texel may exceed every finer
// one there). 16 x 16 x 16 kWeatherLevels RGBA8: level k's blocks at z + 16 k.
std::vector<uint8_t> weather_occupancy(const std::vector<uint8_t>& level0, const std::vector<uint8_t>& levels,
                                       int size);

}  // namespace welkin::clouds
