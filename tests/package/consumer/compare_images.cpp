// compare_images A.png B.png MEAN_STEPS FAR_STEPS FAR_FRACTION
// How far two 8-bit images of one size are apart over their colour channels: the mean absolute
// difference in steps of 255, and the fraction of pixels whose largest channel difference exceeds
// FAR_STEPS. Prints both; exits 1 when the mean exceeds MEAN_STEPS or the fraction FAR_FRACTION.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "welkin/gfx/image.h"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: compare_images A.png B.png MEAN_STEPS FAR_STEPS FAR_FRACTION\n");
    return 2;
  }
  try {
    const welkin::ImageU8 a = welkin::read_png(argv[1]), b = welkin::read_png(argv[2]);
    if (a.width != b.width || a.height != b.height) {
      std::fprintf(stderr, "compare_images: %dx%d against %dx%d\n", a.width, a.height, b.width, b.height);
      return 1;
    }
    const double mean_limit = std::atof(argv[3]), far_fraction_limit = std::atof(argv[5]);
    const int far_steps = std::atoi(argv[4]);
    double sum = 0.0;
    long far = 0;
    const long pixels = long(a.width) * a.height;
    for (long i = 0; i < pixels; ++i) {
      int worst = 0;
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(a.rgba[size_t(i) * 4 + c]) - int(b.rgba[size_t(i) * 4 + c]));
        sum += d;
        worst = std::max(worst, d);
      }
      far += worst > far_steps;
    }
    const double mean = sum / (3.0 * double(pixels)), far_fraction = double(far) / double(pixels);
    std::printf("mean %.3f steps (limit %.3f), %.4f of the pixels beyond %d steps (limit %.4f)\n", mean,
                mean_limit, far_fraction, far_steps, far_fraction_limit);
    return mean <= mean_limit && far_fraction <= far_fraction_limit ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_images: %s\n", e.what());
    return 1;
  }
}
