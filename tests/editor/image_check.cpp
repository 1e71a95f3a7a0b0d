// welkin_editor_image_check FILE.png|FILE.exr [--min-width N --min-height N]
// Exits 0 when the image is not blank: enough distinct colours and contrast (PNG), or finite,
// non-negative and not all zero (EXR). Prints what it measured. Used by smoke_test.sh.
// welkin_editor_image_check A.exr --same-as B.exr --max-relative-l1 T
// Exits 0 when both are the same size and sum |A - B| / sum |B| over the colour channels is at most
// T (0: byte for byte). Prints the measured value and the largest difference. Used by viewport_test.sh.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>

#include "welkin/core/error.h"
#include "welkin/gfx/image.h"

namespace {

int compare_exr(const std::string& a_file, const std::string& b_file, double tolerance) {
  const welkin::ImageF a = welkin::read_exr(a_file), b = welkin::read_exr(b_file);
  if (a.width != b.width || a.height != b.height) {
    std::printf("%s is %dx%d, %s %dx%d\n", a_file.c_str(), a.width, a.height, b_file.c_str(), b.width, b.height);
    return 1;
  }
  double diff = 0, sum = 0, largest = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const double d = std::abs(double(a.rgba[i + c]) - double(b.rgba[i + c]));
      diff += d;
      sum += std::abs(double(b.rgba[i + c]));
      largest = std::max(largest, d);
    }
  const double relative = sum > 0 ? diff / sum : (diff > 0 ? 1.0 : 0.0);
  std::printf("%s against %s: relative L1 %.6g (at most %.6g), largest difference %.6g\n", a_file.c_str(), b_file.c_str(), relative,
              tolerance, largest);
  return std::isfinite(relative) && (tolerance > 0 ? relative <= tolerance : diff == 0) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 6 && !std::strcmp(argv[2], "--same-as") && !std::strcmp(argv[4], "--max-relative-l1")) {
    try {
      return compare_exr(argv[1], argv[3], std::atof(argv[5]));
    } catch (const welkin::Error& e) {
      std::fprintf(stderr, "%s\n", welkin::format_error(e.info()).c_str());
      return 1;
    }
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE.png|FILE.exr [--min-width N] [--min-height N]\n", argv[0]);
    return 2;
  }
  std::string file = argv[1];
  int min_w = 16, min_h = 16;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--min-width")) min_w = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--min-height")) min_h = std::atoi(argv[i + 1]);
  }
  try {
    if (file.size() > 4 && file.substr(file.size() - 4) == ".exr") {
      welkin::ImageF img = welkin::read_exr(file);
      double sum = 0;
      size_t bad = 0;
      for (size_t i = 0; i < img.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
          float v = img.rgba[i + size_t(c)];
          if (!std::isfinite(v) || v < 0) ++bad;
          else sum += v;
        }
      std::printf("%s: %dx%d, mean %.4g, %zu bad values\n", file.c_str(), img.width, img.height,
                  sum / std::max<size_t>(1, img.rgba.size() / 4 * 3), bad);
      return img.width >= min_w && img.height >= min_h && bad == 0 && sum > 0 ? 0 : 1;
    }
    welkin::ImageU8 img = welkin::read_png(file);
    std::set<uint32_t> colours;
    double sum = 0, sum2 = 0;
    size_t n = size_t(img.width) * img.height;
    for (size_t i = 0; i < n; ++i) {
      const uint8_t* p = &img.rgba[i * 4];
      colours.insert(uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]);
      double luma = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      sum += luma;
      sum2 += luma * luma;
    }
    double mean = sum / double(std::max<size_t>(n, 1));
    double stddev = std::sqrt(std::max(0.0, sum2 / double(std::max<size_t>(n, 1)) - mean * mean));
    std::printf("%s: %dx%d, %zu colours, mean luma %.1f, stddev %.1f\n", file.c_str(), img.width, img.height, colours.size(), mean,
                stddev);
    return img.width >= min_w && img.height >= min_h && colours.size() >= 16 && stddev >= 4.0 ? 0 : 1;
  } catch (const welkin::Error& e) {
    std::fprintf(stderr, "%s\n", welkin::format_error(e.info()).c_str());
    return 1;
  }
}
