#pragma once
// The picture every "real time against the path tracer" comparison writes: the approximation's image
// above the reference's (one exposure for both, the reference's 97th percentile of luminance, and a
// 1/2.2 curve) and their signed relative difference below (red: too bright, blue: too dark, full at
// `full_scale`). Each sample is drawn as a cell x cell block.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace welkin::cli {

struct ComparisonPanels {
  int width = 0, height = 0;               // samples across and down
  std::vector<glm::dvec3> approximation;  // row by row, the top row first
  std::vector<glm::dvec3> reference;
  std::vector<double> relative;  // signed relative difference per sample
};

void write_comparison_panels(const std::string& path, const ComparisonPanels& panels, int cell, double full_scale);

}  // namespace welkin::cli
