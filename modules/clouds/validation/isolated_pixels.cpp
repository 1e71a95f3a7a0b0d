#include "validation/isolated_pixels.h"

#include <algorithm>
#include <cmath>

namespace welkin::clouds {

IsolatedPixels count_isolated_pixels(const std::vector<double>& image, int width, int height, double least) {
  IsolatedPixels n;
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      double around[8];
      int k = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx != 0 || dy != 0) around[k++] = image[size_t(y + dy) * size_t(width) + size_t(x + dx)];
      const double v = image[size_t(y) * size_t(width) + size_t(x)];
      if (!std::isfinite(v)) {
        ++n.not_finite;
        continue;
      }
      const auto [lo, hi] = std::minmax_element(around, around + 8);
      if (*lo > least && v * kOutsideFactor < *lo) ++n.holes;
      if (v > least && v > kOutsideFactor * *hi) ++n.fireflies;
      std::nth_element(around, around + 4, around + 8);
      const double median = 0.5 * (around[4] + *std::max_element(around, around + 4));
      if (median > least && (v > kMedianFactor * median || v * kMedianFactor < median)) ++n.off_median;
    }
  return n;
}

}  // namespace welkin::clouds
