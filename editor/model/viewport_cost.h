#pragma once
// What the viewport spends on a frame. How much of it a moving frame renders (the frame's camera's
// moving_render_scale, which the renderer applies while the view moves; a still view renders whole
// and the modules then keep what they drew), and when a still view's last frame is simply shown. The editor's viewport adapts it to a frame budget: a step smaller after a moving
// frame over the budget, a step larger after one well under it, in eighths of the viewport's side
// (so that the render targets change size rarely) within [min_scale, 1].
#include <cstdint>

namespace welkin::editor {

struct MovingScale {
  double budget_ms = 100.0;  // a moving frame's target (10 fps); 0: the camera's own scale, unchanged
  double min_scale = 0.25;
  double scale = 0.0;        // the current one; 0 until the first frame (then the camera's, or 0.5)

  // The scale for this frame, given the camera's moving_render_scale.
  float for_camera(float camera_scale);
  // After a frame rendered at the moving scale that took frame_ms (the editor's whole frame).
  void after_moving_frame(double frame_ms);
};

}  // namespace welkin::editor

namespace welkin::editor {

// A still view's frame kept once it has settled: when what the frame is made from (its digest: the
// scene's components, the view, the size, the clock, the document's versions) has been the same
// for `frames` frames in a row, the modules have converged (the clouds' temporal blocks, the kept
// sky, terrain and cascades) and the next frames would be the same bytes, so the viewport shows the
// last one instead of rendering. Any change renders again at once.
struct SettledView {
  int frames = 24;  // 0: never kept (every frame rendered)
  uint64_t digest = 0;
  int same = 0;     // frames in a row rendered with this digest

  // Whether this frame (of `now`'s digest) may show the last frame instead of rendering.
  bool keep(uint64_t now) {
    if (now != digest) digest = now, same = 0;
    if (frames > 0 && same >= frames) return true;
    ++same;
    return false;
  }
};

}  // namespace welkin::editor
