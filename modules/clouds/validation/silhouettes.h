#pragma once
// Silhouettes after the temporal upscaling (issue 35): frames upscaled from one pixel of each block per
// frame against a march of every pixel of the same view, measured at the full march's silhouettes (where
// its opacity changes by more than 0.1 between neighbouring march pixels), still, turning (as `welkin
// bench --turn-deg 1`) and flying. Shared by `welkin accuracy clouds` and the tests.
#include <cstddef>
#include <string>

#include "welkin/gfx/image.h"

namespace welkin {
class World;
class Renderer;
}  // namespace welkin

namespace welkin::clouds {

struct SilhouetteError {
  double silhouette = 0.0;  // mean |upscaled - full| luminance at silhouette pixels / the frame's mean
  double opacity = 0.0;     // mean |upscaled - full| opacity of the clouds at the march's silhouette texels
  double frame = 0.0;       // relative L1 of the luminance over the frame
  size_t pixels = 0;        // silhouette pixels of the frame
  // The march texels whose 3 x 3 neighbourhood spans more than the step in the full march's opacity:
  // about what the march at silhouettes takes again (clouds/silhouettes_mark.glsl), of all.
  double near_silhouette = 0.0;
};

// The last frame's clouds: radiance (premultiplied) and transmittance at the march's resolution, as
// the resolve wrote them (the temporal upscaling on; row by row from the top, as Renderer::read_hdr).
ImageF clouds_result(World& world);
// The next frame marches every pixel and takes it as it is (its history forgotten): the full march
// of the view, same quality, same jitter, with its opacity readable by clouds_result.
void forget_clouds_history(World& world);

// The frames (width x height) and the clouds (the march's size) of an upscaled view and of the full
// march of the same view. Silhouette pixels: those whose march texel (the nearest) differs in opacity
// from one of its four neighbours by more than `opacity_step`; the frame's border is left out.
SilhouetteError silhouette_error(const ImageF& upscaled_frame, const ImageF& upscaled_clouds,
                                 const ImageF& full_frame, const ImageF& full_clouds,
                                 double opacity_step = 0.1);

enum class SilhouetteMotion { still, turning, flying };
const char* motion_name(SilhouetteMotion motion);

// A world and its renderer, not yet rendered.
struct RenderedWorld {
  World& world;
  Renderer& renderer;
};

// Two worlds of the same scene, each with the temporal upscaling on (`full` forgets its history every
// frame), rendered `settle + frames` frames (indices and times from 0, as `welkin bench`) of width x height:
// still, turning 1 degree a frame (the camera's heading, as `welkin bench --turn-deg 1`), or flying 45 m a
// frame, climbing, turning 0.6 degrees a frame (from the scene's camera position and heading). The mean over
// the last `frames`. `last_upscaled` and `last_full`, when given, receive the last frames.
SilhouetteError measure_silhouettes(RenderedWorld upscaled, RenderedWorld full, SilhouetteMotion motion,
                                    int settle, int frames, int width, int height,
                                    ImageF* last_upscaled = nullptr, ImageF* last_full = nullptr);

}  // namespace welkin::clouds
