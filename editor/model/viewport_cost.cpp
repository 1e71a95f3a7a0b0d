#include "model/viewport_cost.h"

#include <algorithm>
#include <cmath>

namespace welkin::editor {

namespace {

constexpr double kStep = 0.125;  // an eighth of the viewport's side
// Up only when a step larger (at most (n + 1)^2 / n^2 = 1.56 times the pixels from half size up)
// would still fit the budget: no back and forth between two steps.
constexpr double kGrowBelow = 0.6;

}  // namespace

float MovingScale::for_camera(float camera_scale) {
  if (budget_ms <= 0.0) return camera_scale;
  if (scale <= 0.0) scale = camera_scale < 1.0f ? double(camera_scale) : 0.5;
  scale = std::clamp(std::round(scale / kStep) * kStep, std::max(min_scale, kStep), 1.0);
  return float(scale);
}

void MovingScale::after_moving_frame(double frame_ms) {
  if (budget_ms <= 0.0 || scale <= 0.0) return;
  if (frame_ms > budget_ms) scale = std::max(scale - kStep, std::max(min_scale, kStep));
  else if (frame_ms < kGrowBelow * budget_ms) scale = std::min(scale + kStep, 1.0);
}

}  // namespace welkin::editor
