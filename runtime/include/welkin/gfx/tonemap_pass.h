#pragma once
// The frame's last pass: exposure, a tone curve and the sRGB encoding from the HDR colour into the
// 8-bit output, upscaling bilinearly where the colour is smaller (a moving view). Fragment or compute
// form (welkin/gfx/screen_pass.h); the start-up measurement times this pass in both.
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/screen_pass.h"

namespace welkin {

class ShaderLibrary;

struct ToneMap {
  int tonemapper = 0;  // Tonemapper: 0 ACES, 1 AgX, 2 linear
  float exposure = 1.0f;
};
// `empty_vao`: a vertex array for the fragment form's generated triangle.
void run_tonemap(ShaderLibrary& shaders, GLuint empty_vao, const Texture& hdr, const Texture& output,
                 const ToneMap& tm, PassForm form);

}  // namespace welkin
