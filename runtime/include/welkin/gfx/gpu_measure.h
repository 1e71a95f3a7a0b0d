#pragma once
// Measuring GPU work the way peers are measured: forced to completion, and against the floor of
// any full-screen pass (a texel copy of the same size) timed in the same run.
#include <functional>

#include "welkin/gfx/gl_objects.h"

namespace welkin {

class ShaderLibrary;

// Milliseconds for `work` forced to completion (glFinish before and after). On llvmpipe GPU
// timestamps are taken at submission, not when the work runs, so wall time is the honest figure.
double finished_ms(const std::function<void()>& work);

// Median milliseconds of a full-screen RGBA16F texel copy at this size, over `repeats` runs.
double fullscreen_copy_floor_ms(ShaderLibrary& shaders, int width, int height, int repeats = 31);

}  // namespace welkin
