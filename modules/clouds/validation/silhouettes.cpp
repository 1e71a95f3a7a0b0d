#include "silhouettes.h"

#include <algorithm>
#include <cmath>

#include "clouds_gpu.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

namespace {

double luminance(const ImageF& im, int x, int y) {
  const float* p = &im.rgba[(size_t(y) * im.width + x) * 4];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

double opacity(const ImageF& clouds, int x, int y) {
  return 1.0 - clouds.rgba[(size_t(y) * clouds.width + x) * 4 + 3];
}

// The march texel's largest opacity step to one of its four neighbours.
double opacity_step_at(const ImageF& clouds, int x, int y) {
  const double a = opacity(clouds, x, y);
  double step = 0.0;
  if (x > 0) step = std::max(step, std::abs(a - opacity(clouds, x - 1, y)));
  if (x + 1 < clouds.width) step = std::max(step, std::abs(a - opacity(clouds, x + 1, y)));
  if (y > 0) step = std::max(step, std::abs(a - opacity(clouds, x, y - 1)));
  if (y + 1 < clouds.height) step = std::max(step, std::abs(a - opacity(clouds, x, y + 1)));
  return step;
}

Camera& camera_of(World& world) {
  return *world.registry().get<Camera>(world.registry().first<Camera>());
}

}  // namespace

ImageF clouds_result(World& world) {
  CloudsGpu& gpu = world.resource<CloudsGpu>();
  if (!gpu.history_valid || !gpu.history_color[1 - gpu.history_index])
    throw Error(ErrorInfo{.message = "the clouds kept no result (temporal upscaling off, or no frame yet)"});
  return read_texture_float(*gpu.history_color[1 - gpu.history_index]);
}

void forget_clouds_history(World& world) {
  world.resource<CloudsGpu>().history_valid = false;
}

SilhouetteError silhouette_error(const ImageF& upscaled_frame, const ImageF& upscaled_clouds,
                                 const ImageF& full_frame, const ImageF& full_clouds, double opacity_step) {
  const int w = full_frame.width, h = full_frame.height, mw = full_clouds.width, mh = full_clouds.height;
  if (upscaled_frame.width != w || upscaled_frame.height != h || upscaled_clouds.width != mw ||
      upscaled_clouds.height != mh)
    throw Error(ErrorInfo{.message = "silhouettes: the upscaled and the full frames differ in size"});
  SilhouetteError e;
  double mean = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) mean += luminance(full_frame, x, y);
  mean /= double(w) * h;
  double edge_sum = 0.0, frame_sum = 0.0, frame_total = 0.0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const double l = luminance(full_frame, x, y), d = std::abs(luminance(upscaled_frame, x, y) - l);
      frame_sum += d, frame_total += l;
      const int mx = std::min(x * mw / w, mw - 1), my = std::min(y * mh / h, mh - 1);
      if (opacity_step_at(full_clouds, mx, my) > opacity_step) edge_sum += d, ++e.pixels;
    }
  size_t texels = 0, near = 0;
  for (int y = 0; y < mh; ++y)
    for (int x = 0; x < mw; ++x) {
      if (opacity_step_at(full_clouds, x, y) > opacity_step)
        e.opacity += std::abs(opacity(upscaled_clouds, x, y) - opacity(full_clouds, x, y)), ++texels;
      double lo = 1.0, hi = 0.0;
      for (int j = std::max(y - 1, 0); j <= std::min(y + 1, mh - 1); ++j)
        for (int i = std::max(x - 1, 0); i <= std::min(x + 1, mw - 1); ++i)
          lo = std::min(lo, opacity(full_clouds, i, j)), hi = std::max(hi, opacity(full_clouds, i, j));
      if (hi - lo > opacity_step) ++near;
    }
  e.near_silhouette = double(near) / (double(mw) * mh);
  e.silhouette = edge_sum / double(std::max<size_t>(e.pixels, 1)) / std::max(mean, 1e-30);
  e.opacity /= double(std::max<size_t>(texels, 1));
  e.frame = frame_sum / std::max(frame_total, 1e-30);
  return e;
}

const char* motion_name(SilhouetteMotion motion) {
  switch (motion) {
    case SilhouetteMotion::still:
      return "still";
    case SilhouetteMotion::turning:
      return "turning";
    case SilhouetteMotion::flying:
      return "flying";
  }
  return "";
}

SilhouetteError measure_silhouettes(RenderedWorld upscaled, RenderedWorld full, SilhouetteMotion motion,
                                    int settle, int frames, int width, int height, ImageF* last_upscaled,
                                    ImageF* last_full) {
  const glm::dvec3 start_m = camera_of(upscaled.world).position_m;
  const float start_heading = camera_of(upscaled.world).heading_deg;
  SilhouetteError sum;
  for (int f = 0; f < settle + frames; ++f) {
    for (RenderedWorld* r : {&upscaled, &full}) {
      Camera& camera = camera_of(r->world);
      if (motion == SilhouetteMotion::turning) camera.heading_deg = start_heading + float(f);
      if (motion == SilhouetteMotion::flying) {
        camera.position_m = start_m + glm::dvec3(-20.0 * f, -40.0 * f, 5.0 * f);
        camera.heading_deg = start_heading + 0.6f * float(f);
      }
      if (r == &full) forget_clouds_history(r->world);
      r->renderer.render_frame(FrameInfo{.time_s = f / 30.0, .dt_s = 1.0 / 30.0, .index = uint64_t(f)}, width,
                               height);
    }
    if (f < settle) continue;
    const ImageF a = upscaled.renderer.read_hdr(), b = full.renderer.read_hdr();
    const SilhouetteError e =
        silhouette_error(a, clouds_result(upscaled.world), b, clouds_result(full.world));
    sum.silhouette += e.silhouette, sum.opacity += e.opacity, sum.frame += e.frame, sum.pixels += e.pixels;
    sum.near_silhouette += e.near_silhouette;
    if (f + 1 == settle + frames) {
      if (last_upscaled) *last_upscaled = a;
      if (last_full) *last_full = b;
    }
  }
  const double n = std::max(frames, 1);
  sum.silhouette /= n, sum.opacity /= n, sum.frame /= n, sum.near_silhouette /= n,
      sum.pixels = size_t(double(sum.pixels) / n);
  return sum;
}

}  // namespace welkin::clouds
