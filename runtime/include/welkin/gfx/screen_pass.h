#pragma once
// Full-screen passes in two forms behind one interface: a fragment shader over a full-screen
// triangle, or a compute shader over tiles of pixels (welkin/screen_pass.glsl). Which form runs is
// measured per device when the first renderer starts, not chosen by the user: on the lent H100 the
// compute form of the same arithmetic ran 8-32 times faster (its raster hardware is a small part of the
// chip), on llvmpipe it ran 10-70% slower (it bins and shades fragments in SIMD blocks with early
// depth tests, and runs a work group as a loop over its invocations).
#include <map>
#include <string>

#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_objects.h"

namespace welkin {

class Program;
class ShaderLibrary;

enum class PassForm { fragment, compute };
const char* pass_form_name(PassForm form);

// The start-up measurement: the tone map, both forms, the same pixels (the fastest of several runs, ms).
struct PassFormProbe {
  double fragment_ms = 0.0, compute_ms = 0.0;
  int width = 0, height = 0;
  PassForm chosen = PassForm::fragment;
};
// Times the tone map in both forms on the current context; compute is chosen where it takes at most
// half the fragment form's time. On the H100 a copy took an eighth as compute, on llvmpipe 1.1-1.7 times
// as long; under a shared machine's load (6 agents on 2 cores) a probe on llvmpipe once came to 0.8,
// and forms that cost about the same keep the fragment one, whose passes skip pixels by the depth test.
PassFormProbe probe_pass_form(ShaderLibrary& shaders, int width = 512, int height = 288, int repeats = 7);
// The probe's result for the current GL renderer, measured once per process and renderer.
const PassFormProbe& device_pass_form(ShaderLibrary& shaders);

// The form each full-screen pass takes: the device's, unless a test or a benchmark forces one (by pass
// name, or "*" for every pass).
struct PassForms {
  PassForm device = PassForm::fragment;
  bool measured = false;
  std::map<std::string, PassForm> forced;
  PassForm of(const std::string& pass) const;
  bool compute(const std::string& pass) const { return of(pass) == PassForm::compute; }
};

// Compute form: work groups of kScreenTileX x kScreenTileY invocations, one pixel each, over `pixels`
// (uniforms u_pixel_origin and u_pixel_end of welkin/screen_pass.glsl), then a barrier for every
// kind of reader after it (a fragment pass drawing into the same target, a copy, a readback).
constexpr int kScreenTileX = 8, kScreenTileY = 8;
void dispatch_screen(const Program& program, const PixelRect& pixels);
// The part of a rectangle inside a width x height frame (what a scissor would leave of it).
PixelRect clipped(const PixelRect& r, int width, int height);
// Binds level 0 of a 2D texture as an image for load and store at `unit`.
void bind_image_read_write(GLuint unit, const Texture& texture);
// The GLSL image format qualifier of a texture format (rgba16f, rgba8, ...).
const char* image_format_qualifier(TextureFormat format);

}  // namespace welkin
