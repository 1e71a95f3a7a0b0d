#pragma once
// Measuring GPU work the way peers are measured: forced to completion, and against the floor of
// any full-screen pass (a texel copy of the same size) timed in the same run.
#include <functional>
#include <memory>

#include "welkin/gfx/gl_objects.h"

namespace welkin {

class ShaderLibrary;
class Program;

// Milliseconds for `work` forced to completion (glFinish before and after). On llvmpipe GPU
// timestamps are taken at submission, not when the work runs, so wall time is the honest figure.
double finished_ms(const std::function<void()>& work);

// A full-screen RGBA16F texel copy at one size, kept ready so that it can be timed between the
// frames of a benchmark (a shared machine's speed drifts: a ratio is honest only against a floor
// measured at the same time).
class CopyFloor {
 public:
  CopyFloor(ShaderLibrary& shaders, int width, int height);
  ~CopyFloor();
  CopyFloor(const CopyFloor&) = delete;
  CopyFloor& operator=(const CopyFloor&) = delete;
  // Median milliseconds over `repeats` copies.
  double measure_ms(int repeats);

 private:
  Texture src_, dst_;
  Framebuffer fb_;
  GLuint vao_ = 0;
  const Program& program_;
};

// Median milliseconds of a full-screen RGBA16F texel copy at this size, over `repeats` runs.
double fullscreen_copy_floor_ms(ShaderLibrary& shaders, int width, int height, int repeats = 31);

}  // namespace welkin
