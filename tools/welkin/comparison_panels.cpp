#include "comparison_panels.h"

#include <algorithm>
#include <cmath>

#include "welkin/gfx/image.h"

namespace welkin::cli {

void write_comparison_panels(const std::string& path, const ComparisonPanels& p, int cell, double full_scale) {
  constexpr int kGap = 4;
  const int w = p.width, h = p.height;
  auto luminance = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  std::vector<double> sorted;
  for (const glm::dvec3& c : p.reference) sorted.push_back(luminance(c));
  std::sort(sorted.begin(), sorted.end());
  const double exposure = sorted.empty() ? 1.0 : std::max(sorted[size_t(0.97 * double(sorted.size() - 1))], 1e-30);
  ImageU8 img;
  img.width = w * cell;
  img.height = 3 * h * cell + 2 * kGap;
  img.rgba.assign(size_t(img.width) * img.height * 4, 255);
  auto fill = [&](int panel, int x, int y, glm::dvec3 c) {
    for (int dy = 0; dy < cell; ++dy)
      for (int dx = 0; dx < cell; ++dx) {
        uint8_t* px = &img.rgba[(size_t(panel * (h * cell + kGap) + y * cell + dy) * img.width + x * cell + dx) * 4];
        for (int k = 0; k < 3; ++k) px[k] = uint8_t(std::lround(255.0 * std::clamp(c[k], 0.0, 1.0)));
      }
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      for (int panel = 0; panel < 2; ++panel) {
        const glm::dvec3 c = (panel == 0 ? p.approximation[i] : p.reference[i]) / exposure;
        fill(panel, x, y, glm::pow(glm::max(c, glm::dvec3(0.0)), glm::dvec3(1.0 / 2.2)));
      }
      const double rel = p.relative[i], a = std::min(std::abs(rel) / full_scale, 1.0);
      fill(2, x, y, rel > 0 ? glm::dvec3(1.0, 1.0 - a, 1.0 - a) : glm::dvec3(1.0 - a, 1.0 - a, 1.0));
    }
  write_png(path, img);
}

}  // namespace welkin::cli
