// The weather volume's coarser levels, each equalised as level 0 is, and the empty-space skip's
// occupancy over them (weather_levels.h).
#include "weather_levels.h"

#include <algorithm>
#include <cmath>

namespace welkin::clouds {

std::vector<uint8_t> equalised(const std::vector<uint32_t>& keys) {
  const size_t n = keys.size();
  std::vector<uint8_t> out(n);
  if (n == 0) return out;
  auto value = [n](double below, double count) {
    return uint8_t(std::lround(255.0 * (below + 0.5 * count) / double(n)));
  };
  const uint32_t top = *std::max_element(keys.begin(), keys.end());
  if (top < 65536) {
    // Few possible keys (a byte volume's texels, the sums of a fine level): counted in a histogram.
    std::vector<double> histogram(size_t(top) + 1, 0.0);
    for (uint32_t k : keys) histogram[k] += 1.0;
    std::vector<uint8_t> map(histogram.size());
    double below = 0.0;
    for (size_t v = 0; v < histogram.size(); ++v) map[v] = value(below, histogram[v]), below += histogram[v];
    for (size_t i = 0; i < n; ++i) out[i] = map[keys[i]];
    return out;
  }
  std::vector<uint32_t> sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < n; ++i) {
    const auto [first, last] = std::equal_range(sorted.begin(), sorted.end(), keys[i]);
    out[i] = value(double(first - sorted.begin()), double(last - first));
  }
  return out;
}

std::vector<uint8_t> weather_levels(const std::vector<uint8_t>& level0, int size) {
  // The sums of level 0 over each texel of a level: exact integers, so ranks follow the average's order.
  std::vector<uint32_t> sums(level0.begin(), level0.end());
  std::vector<uint8_t> out;
  for (int s = size / 2, finer = size; s >= 1; finer = s, s /= 2) {
    const size_t n = size_t(s) * size_t(s) * size_t(s);
    std::vector<uint32_t> next(n * 4, 0);
    for (int z = 0; z < s; ++z)
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
          for (int k = 0; k < 8; ++k) {
            const size_t from =
                (size_t(2 * z + (k >> 2)) * size_t(finer) + size_t(2 * y + ((k >> 1) & 1))) * size_t(finer) +
                size_t(2 * x + (k & 1));
            for (size_t c = 0; c < 4; ++c) next[((size_t(z) * s + y) * s + x) * 4 + c] += sums[from * 4 + c];
          }
    sums = std::move(next);
    const double texels_in_one = double(size / s) * double(size / s) * double(size / s);
    std::vector<uint8_t> level(n * 4);
    std::vector<uint32_t> keys(n);
    for (size_t c = 0; c < 4; ++c) {
      for (size_t i = 0; i < n; ++i) keys[i] = sums[i * 4 + c];
      if (int(c) < kWeatherEqualisedChannels) {
        const std::vector<uint8_t> v = equalised(keys);
        for (size_t i = 0; i < n; ++i) level[i * 4 + c] = v[i];
      } else {
        for (size_t i = 0; i < n; ++i)
          level[i * 4 + c] = uint8_t(std::lround(double(keys[i]) / texels_in_one));
      }
    }
    out.insert(out.end(), level.begin(), level.end());
  }
  return out;
}

std::vector<uint8_t> weather_occupancy(const std::vector<uint8_t>& level0, const std::vector<uint8_t>& levels,
                                       int size) {
  const int b = kWeatherOccupancySize, per = size / b;
  std::vector<uint8_t> out(size_t(b) * b * b * kWeatherLevels * 4, 0);
  auto entry = [b](int level, int x, int y, int z) { return ((size_t(level * b + z) * b + y) * b + x) * 4; };
  const uint8_t* texels = level0.data();
  for (int level = 0, s = size; level < kWeatherLevels; ++level, texels += size_t(s) * s * s * 4, s /= 2) {
    if (level == 1) texels = levels.data();
    const double scale = double(size / s);
    auto at = [&](int x, int y, int z, int c) {
      auto w = [s](int v) { return size_t(((v % s) + s) % s); };
      return texels[((w(z) * size_t(s) + w(y)) * size_t(s) + w(x)) * 4 + size_t(c)];
    };
    // A linear filter at a point reads the texels either side of it: for the points of a block (from
    // its near side to its far side) the one before its first texel centre to the one after its last.
    auto first = [&](int block) { return int(std::floor(block * per / scale - 0.5)); };
    auto last = [&](int block) { return int(std::floor((block + 1) * per / scale - 0.5)) + 1; };
    for (int z = 0; z < b; ++z)
      for (int y = 0; y < b; ++y)
        for (int x = 0; x < b; ++x)
          for (int c = 0; c < kWeatherEqualisedChannels; ++c) {
            uint8_t m = level > 0 ? out[entry(level - 1, x, y, z) + size_t(c)] : 0;
            for (int k = first(z); k <= last(z); ++k)
              for (int j = first(y); j <= last(y); ++j)
                for (int i = first(x); i <= last(x); ++i) m = std::max(m, at(i, j, k, c));
            out[entry(level, x, y, z) + size_t(c)] = m;
          }
  }
  return out;
}

}  // namespace welkin::clouds
