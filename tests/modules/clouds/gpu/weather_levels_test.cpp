// The weather's mip levels (src/weather_levels.h): each level's coverage channels equalised as level
// 0 is, so that a coverage c covers c of the texels at every level the march reads far away, and the
// empty-space skip's occupancy holding every value a linear read at those levels can give in its block.
#include "weather_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <vector>

#include "clouds_test_support.h"

namespace welkin::clouds {
namespace {

// Level `level` of an RGBA8 cube texture, read back from the GL.
std::vector<uint8_t> read_level(const Texture& t, int level) {
  const int s = std::max(t.desc().width >> level, 1);
  std::vector<uint8_t> bytes(size_t(s) * size_t(s) * size_t(s) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(t.id(), level, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  return bytes;
}

// The average of level 0's channel c over each texel of a level `s` texels a side (a box filter).
std::vector<double> box_average(const std::vector<uint8_t>& level0, int size, int s, int c) {
  const int f = size / s;
  std::vector<double> out(size_t(s) * s * s, 0.0);
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        out[(size_t(z / f) * s + size_t(y / f)) * s + size_t(x / f)] +=
            level0[((size_t(z) * size + y) * size + x) * 4 + size_t(c)] / (255.0 * f * f * f);
  return out;
}

double fraction_below(const std::vector<double>& v, double q) {
  return double(std::count_if(v.begin(), v.end(), [q](double x) { return x < q; })) / double(v.size());
}

TEST(CloudsWeatherLevels, EveryLevelIsEqualisedSoCoverageIsTheCoveredFraction) {
  test::Rendered r = test::render(test::noon());
  const Texture& weather = *r.world->resource<CloudsGpu>().weather;
  const int size = weather.desc().width;
  ASSERT_EQ(size, kWeatherNoiseSize);
  const std::vector<uint8_t> level0 = read_level(weather, 0);
  // Levels 1 to 4 (32^3 to 4^3 texels; the coarser two hold 8 and 1).
  for (int level = 1; level <= 4; ++level) {
    const int s = size >> level;
    const std::vector<uint8_t> texels = read_level(weather, level);
    for (int c = 0; c < 4; ++c) {
      const std::vector<double> average = box_average(level0, size, s, c);
      std::vector<double> stored(average.size());
      for (size_t i = 0; i < stored.size(); ++i) stored[i] = texels[i * 4 + size_t(c)] / 255.0;
      if (c == 3) {
        // The base's variation, which moves the base linearly: the plain average.
        for (size_t i = 0; i < stored.size(); ++i)
          ASSERT_NEAR(stored[i], average[i], 0.51 / 255.0) << "level " << level << " texel " << i;
        continue;
      }
      for (double q : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        // A coverage 1 - q covers the texels at or over q: their share is 1 - q.
        EXPECT_NEAR(fraction_below(stored, q), q, 0.02)
            << "level " << level << " channel " << c << " quantile " << q;
      }
      // What plain averages would hold: crowded toward the middle (a coverage of 0.3, over 0.7,
      // covering a far smaller share).
      // Plain averages crowd toward the middle: from level 2 on a coverage of 0.3 (the texels over
      // 0.7) would cover less than 0.26 of them (at level 4 none), outside the tolerance above.
      if (level >= 2) {
        EXPECT_GT(fraction_below(average, 0.7), 0.74) << "level " << level << " channel " << c;
      }
      // The equalised level keeps the averages' order: it is the average weather, only spread.
      std::vector<size_t> order(average.size());
      std::iota(order.begin(), order.end(), size_t(0));
      std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return average[a] < average[b]; });
      for (size_t i = 1; i < order.size(); ++i)
        if (average[order[i - 1]] < average[order[i]]) {
          ASSERT_LE(stored[order[i - 1]], stored[order[i]]) << "level " << level << " channel " << c;
        }
    }
  }
}

// A linear read of channel c of a level (s texels a side, wrapping) at uvw.
double linear_read(const std::vector<uint8_t>& texels, int s, glm::dvec3 uvw, int c) {
  const glm::dvec3 u = uvw * double(s) - 0.5, f = u - glm::floor(u);
  const glm::ivec3 i0(glm::floor(u));
  double v = 0.0;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o((k & 1), (k >> 1) & 1, k >> 2);
    const glm::ivec3 i = ((i0 + o) % s + s) % s;
    const double w = (o.x ? f.x : 1.0 - f.x) * (o.y ? f.y : 1.0 - f.y) * (o.z ? f.z : 1.0 - f.z);
    v += w * texels[((size_t(i.z) * s + size_t(i.y)) * s + size_t(i.x)) * 4 + size_t(c)];
  }
  return v;
}

TEST(CloudsWeatherLevels, TheOccupancyHoldsEveryReadAtTheLevelsUpToItsOwn) {
  test::Rendered r = test::render(test::noon());
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  const int size = gpu.weather->desc().width, b = kWeatherOccupancySize;
  ASSERT_EQ(gpu.weather_maximum->desc().depth, b * kWeatherLevels);
  std::vector<uint8_t> occupancy(size_t(b) * b * b * kWeatherLevels * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(gpu.weather_maximum->id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(occupancy.size()),
                    occupancy.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  auto entry = [&](int level, glm::ivec3 block, int c) {
    return occupancy[((size_t(level * b + block.z) * b + size_t(block.y)) * b + size_t(block.x)) * 4 +
                     size_t(c)];
  };
  uint32_t state = 12345u;
  auto random = [&state] { return double((state = state * 1664525u + 1013904223u) >> 8) / double(1u << 24); };
  int over_level0 = 0;
  for (int level = 0; level < kWeatherLevels; ++level) {
    const int s = size >> level;
    const std::vector<uint8_t> texels = read_level(*gpu.weather, level);
    for (int n = 0; n < 3000; ++n) {
      const glm::dvec3 uvw(random(), random(), random());
      const glm::ivec3 block = glm::min(glm::ivec3(uvw * double(b)), glm::ivec3(b - 1));
      for (int c = 0; c < kWeatherEqualisedChannels; ++c) {
        const double v = linear_read(texels, s, uvw, c);
        // This level's entry and every coarser one's hold what a read here finds.
        for (int k = level; k < kWeatherLevels; ++k)
          ASSERT_LE(v, entry(k, block, c) + 1e-9) << "level " << level << " entry " << k << " channel " << c;
        over_level0 += v > entry(0, block, c) + 0.5;
      }
    }
  }
  // Coarser levels do read more than level 0's largest texel in places: an occupancy of level 0
  // alone would skip clouds there.
  EXPECT_GT(over_level0, 100);
  std::printf("reads over level 0's maximum: %d\n", over_level0);
  // The skip still finds empty blocks for a coverage of 0.3 (the threshold 0.7): near (level 0) as
  // many as before, and fewer at the coarser levels.
  for (int level = 0; level < kWeatherLevels; ++level) {
    int empty = 0;
    for (int z = 0; z < b; ++z)
      for (int y = 0; y < b; ++y)
        for (int x = 0; x < b; ++x) empty += entry(level, {x, y, z}, 0) < 0.7 * 255.0;
    std::printf("level %d: %d of %d blocks empty under a coverage of 0.3\n", level, empty, b * b * b);
    if (level == 0) {
      EXPECT_GT(empty, b * b * b / 20);
    }
  }
}

}  // namespace
}  // namespace welkin::clouds
