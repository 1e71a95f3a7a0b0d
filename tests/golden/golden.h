#pragma once
// Golden-image comparison for rendering tests. Each test states its tolerance; on failure a diff
// image (|a-b| x 8, alpha opaque) and the actual image are written next to the build's test output
// so the difference can be looked at. Goldens are updated only by tools/update-goldens, after
// looking at them.
#include <string>

#include "welkin/gfx/image.h"

namespace welkin::testing {

struct GoldenTolerance {
  int max_channel_difference = 8;        // per 8-bit channel, for a pixel to count as matching
  double max_failing_fraction = 0.002;   // fraction of pixels allowed to exceed it
};

struct GoldenResult {
  bool passed = false;
  std::string message;  // what differed and where the diff image went
  double failing_fraction = 0;
  int max_difference = 0;
};

// Compares `actual` with the PNG at tests/golden/<name>.png. When WELKIN_UPDATE_GOLDENS=1 is set
// (only tools/update-goldens sets it) the golden is written instead and the comparison passes.
GoldenResult compare_with_golden(const ImageU8& actual, const std::string& name, const GoldenTolerance& tolerance);

}  // namespace welkin::testing
