#pragma once
// Shared by GL benchmarks: a headless context and GPU timing of a draw forced to completion.
#include <functional>

#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/gl_objects.h"

namespace welkin::bench {

GlContext& context();
// Milliseconds for `draw` forced to completion (glFinish before and after), as the peers were measured.
double gpu_ms(const std::function<void()>& draw);
// The floor of any full-screen pass: an RGBA16F texture copied to an RGBA16F target by a fragment shader.
void draw_fullscreen_copy(const Texture& source, const Framebuffer& target);

}  // namespace welkin::bench
