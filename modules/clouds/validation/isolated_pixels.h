// Pixels that stand out of their neighbours in an image of the clouds (a hole, a firefly): what
// `welkin accuracy clouds --image` counts in each march and the tests hold the shipped frame to.
#pragma once
#include <vector>

namespace welkin::clouds {

// Off the 8 neighbours' median by kMedianFactor either way; a hole, below all 8 by kOutsideFactor; a
// firefly, above all 8 by kOutsideFactor. In a smooth image a defect; in an image of one ray a pixel,
// also the field's own detail finer than a pixel (a gap between billows, a thin lit edge).
constexpr double kMedianFactor = 4.0, kOutsideFactor = 2.0;
struct IsolatedPixels {
  int off_median = 0, holes = 0, fireflies = 0, not_finite = 0;
};
// Over the pixels off the image's border (row by row, `width` a row), where the neighbours (or, for a
// firefly, the pixel) are above `least`: the black between clouds is no hole.
IsolatedPixels count_isolated_pixels(const std::vector<double>& image, int width, int height, double least);

}  // namespace welkin::clouds
