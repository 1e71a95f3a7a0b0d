#pragma once
// The "error against run time" plot every `welkin accuracy` technique writes: log-log, one series per
// method, a disc for the relative RMSE and a square for the worst error of each configuration.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace welkin::cli {

struct PlotPoint {
  double ms = 0.0;    // GPU time per frame
  double rmse = 0.0;  // relative RMSE
  double max = 0.0;   // worst relative error
  std::string label;  // e.g. the quality preset
};

struct PlotSeries {
  std::string name;
  glm::u8vec3 colour{0, 0, 0};
  std::vector<PlotPoint> points;  // joined in this order
};

void write_error_plot(const std::string& path, const std::string& title, const std::string& subtitle,
                      const std::string& x_label, const std::vector<PlotSeries>& series);

}  // namespace welkin::cli
