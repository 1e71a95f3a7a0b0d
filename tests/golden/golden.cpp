#include "golden.h"

#include <cstdlib>
#include <filesystem>

#include "welkin/core/error.h"

namespace welkin::testing {

GoldenResult compare_with_golden(const ImageU8& actual, const std::string& name, const GoldenTolerance& tol) {
  namespace fs = std::filesystem;
  fs::path golden = fs::path(WELKIN_SOURCE_DIR) / "tests/golden" / (name + ".png");
  fs::path out_dir = fs::path(WELKIN_BINARY_DIR) / "golden-output";
  // Names carry their folder ("atmosphere/noon"): the images written for review go in the same one.
  fs::create_directories((out_dir / name).parent_path());
  GoldenResult r;
  const char* update = std::getenv("WELKIN_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    fs::create_directories(golden.parent_path());
    write_png(golden.string(), actual);
    r.passed = true;
    r.message = "updated " + golden.string();
    return r;
  }
  if (!fs::exists(golden)) {
    r.message = "missing golden " + golden.string() + " (create it with tools/update-goldens after looking at it)";
    write_png((out_dir / (name + ".actual.png")).string(), actual);
    return r;
  }
  ImageU8 expected = read_png(golden.string());
  if (expected.width != actual.width || expected.height != actual.height) {
    write_png((out_dir / (name + ".actual.png")).string(), actual);
    r.message = "size differs: golden " + std::to_string(expected.width) + "x" + std::to_string(expected.height) +
                ", actual " + std::to_string(actual.width) + "x" + std::to_string(actual.height) + "; wrote " +
                (out_dir / (name + ".actual.png")).string();
    return r;
  }
  ImageU8 diff{actual.width, actual.height, std::vector<uint8_t>(actual.rgba.size(), 255)};
  size_t failing = 0;
  for (size_t p = 0; p < size_t(actual.width) * actual.height; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      int d = std::abs(int(actual.rgba[p * 4 + c]) - int(expected.rgba[p * 4 + c]));
      worst = std::max(worst, d);
      diff.rgba[p * 4 + c] = uint8_t(std::min(255, d * 8));
    }
    r.max_difference = std::max(r.max_difference, worst);
    if (worst > tol.max_channel_difference) ++failing;
  }
  r.failing_fraction = double(failing) / (double(actual.width) * actual.height);
  r.passed = r.failing_fraction <= tol.max_failing_fraction;
  r.message = name + ": " + std::to_string(failing) + " pixels differ by more than " +
              std::to_string(tol.max_channel_difference) + " (fraction " + std::to_string(r.failing_fraction) +
              ", allowed " + std::to_string(tol.max_failing_fraction) + "), max difference " + std::to_string(r.max_difference);
  if (!r.passed) {
    write_png((out_dir / (name + ".actual.png")).string(), actual);
    write_png((out_dir / (name + ".diff.png")).string(), diff);
    r.message += "; wrote " + (out_dir / (name + ".diff.png")).string();
  }
  return r;
}

}  // namespace welkin::testing
