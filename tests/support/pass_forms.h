#pragma once
// Full-screen passes in their two forms (welkin/gfx/screen_pass.h): one frame rendered with every such
// pass in its fragment form, and again with one pass in its compute form, and how far the frames differ.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "welkin/core/world.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"

namespace welkin::testing {

struct FormFrame {
  ImageF hdr;
  ImageU8 output;
  std::vector<std::string> passes;  // the passes that ran
  bool ran(const std::string& name) const {
    return std::find(passes.begin(), passes.end(), name) != passes.end();
  }
};

// One whole frame of a fresh world from `make_world`, every full-screen pass a fragment pass except
// `pass`, which takes `form`.
inline FormFrame render_with_form(const std::function<std::unique_ptr<World>()>& make_world,
                                  const std::string& pass, PassForm form, int width, int height) {
  std::unique_ptr<World> world = make_world();
  Renderer renderer(*world);
  renderer.context().forms.forced["*"] = PassForm::fragment;
  renderer.context().forms.forced[pass] = form;
  const FrameResult r = renderer.render_frame(FrameInfo{.index = 3, .alone = true}, width, height);
  FormFrame f{renderer.read_hdr(), renderer.read_output(), {}};
  for (const auto& t : r.timings) f.passes.push_back(t.name);
  return f;
}

// The largest difference of a colour channel between two HDR frames, relative to the larger of the two
// values, where that exceeds `floor` (a fraction of the frame's brightest channel: below it a
// half float's steps are coarse against the value), else relative to the floor.
struct HdrDifference {
  double worst = 0.0;
  int x = -1, y = -1;
  double brightest = 0.0;
  int pixels_over = 0;  // pixels with a channel differing by more than `over`
};
inline HdrDifference hdr_difference(const ImageF& a, const ImageF& b, double floor_fraction,
                                    double over = 1e30) {
  HdrDifference d;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) d.brightest = std::max(d.brightest, double(std::abs(a.rgba[i])));
  const double floor = std::max(floor_fraction * d.brightest, 1e-30);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool pixel_over = false;
      for (int c = 0; c < 3; ++c) {
        const double p = a.pixel(x, y)[c], q = b.pixel(x, y)[c];
        const double e = std::abs(p - q) / std::max({std::abs(p), std::abs(q), floor});
        if (!(e <= d.worst)) d.worst = e, d.x = x, d.y = y;  // a NaN counts as the worst
        pixel_over = pixel_over || !(e <= over);
      }
      d.pixels_over += pixel_over ? 1 : 0;
    }
  return d;
}

// The largest difference of an 8-bit channel between two outputs.
inline int output_difference(const ImageU8& a, const ImageU8& b) {
  int worst = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
  return worst;
}

}  // namespace welkin::testing
