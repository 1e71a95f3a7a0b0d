#pragma once
// The GPU march against the CPU reference on single view rays through the same cloud field: a world
// with the clouds, a white sun (core.DirectionalLight, 100 klx, no air, no ground bounce) or a sky
// alone (set_light), so that both see exactly the same light, and a frame aimed along each ray (kRows).
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>

#include "reference/cloud_path_tracer.h"
#include "welkin/clouds/components.h"
#include "welkin/core/disk_cache.h"
#include "welkin/gfx/camera.h"

namespace welkin {
class World;
class Renderer;
}  // namespace welkin

namespace welkin::clouds {

struct CloudView {
  std::string name;
  double altitude_m = 100.0;
  double heading_deg = 0.0;  // clockwise from north
  double pitch_deg = 30.0;
  double east_m = 0.0, north_m = 0.0;  // the camera over the scene's origin
};

class CloudProbe {
 public:
  // Requires a current GL 4.5 context. The clouds' temporal upscaling is turned off: every frame marches
  // every ray.
  CloudProbe(const VolumetricClouds& clouds, double sun_azimuth_deg, double sun_elevation_deg);
  ~CloudProbe();
  static constexpr double kSunIlluminance = 100000.0;
  // Each ray is the middle pixel of a frame one pixel wide and kRows high, one degree high: the pixel
  // a 1080p frame 60 degrees high has, so that the march reads the noise at the mip level such a frame
  // reads (it follows the pixel's footprint; a 1x1 frame one degree high read the detail noise 2 km
  // away blurred over 35 m, where the reference sees it sharp). Odd, and odd at every quality's march
  // resolution (ceil(17 x 0.25, 0.4, 0.5, 1) = 5, 7, 9, 17): the middle march pixel is the ray.
  static constexpr int kRows = 17;
  // The march jitters where its steps fall, per pixel and frame, and the temporal resolve averages the
  // frames: a ray's (and an image's) radiance is the mean of this many frames (one frame of a deck's
  // top seen from above is up to 4% off the mean).
  static constexpr int kJitterFrames = 16;

  // What lights the rays, on both sides: the sun alone (as built), or the sky alone, the runtime's
  // default sky with kSkyFraction of the sun's illuminance on a plane facing up, over a black ground.
  // The march cannot turn its sun off, so its share of the sky is its frame with that sky less its
  // frame without (the march is linear in the light); the path tracer sees a uniform sky of radiance
  // kSkyFraction x kSunIlluminance / pi above the planet's horizon, which gives a plane facing up
  // that irradiance.
  enum class Light { sun, sky };
  static constexpr double kSkyFraction = 0.25;
  void set_light(Light light) { light_ = light; }

  // Radiance (cd/m^2, green channel) of the ray through the middle of the frame.
  double gpu_radiance(const CloudView& view);
  // The path-traced radiance of the same ray through the same field (the noise read back); from the
  // reference cache when it holds the same ray, light, settings and field (see set_reference_cache).
  reference::CloudRadianceEstimate reference_radiance(const CloudView& view,
                                                      const reference::PathTraceSettings& settings);
  // Keeps path-traced rays between runs (disabled by default). A ray's key holds the clouds'
  // settings, the sun, the ray, the path tracer's settings, hashes of the noise volumes and the
  // layers, and of the field's extinction at 1024 points along the ray: a change to the field's
  // code or data that the ray can see reads as a miss.
  void set_reference_cache(DiskCache cache) { cache_ = std::move(cache); }
  // Median GPU milliseconds of the clouds' passes per frame of width x height, and of a copy.
  struct Cost {
    double clouds_ms = 0.0, copy_ms = 0.0;
  };
  // The frame `camera` sees (its position, heading, pitch, roll and field of view), width x height,
  // row by row from the top: the radiance (green) marched with the probe's clouds, and path traced
  // through the same field (settings.samples paths per pixel; pixels shared among settings.threads
  // workers, each pixel its own seed, so the image does not depend on the thread count). The path-traced
  // image is kept in the reference cache whole, keyed by every pixel's ray key (set_reference_cache).
  std::vector<double> gpu_image(const Camera& camera, int width, int height);
  std::vector<reference::CloudRadianceEstimate> reference_image(const Camera& camera, int width, int height,
                                                                const reference::PathTraceSettings& settings);
  // The view turns by turn_deg a frame, so that the temporal upscaling marches every frame (a still view
  // keeps its clouds and skips the march).
  Cost cost(const CloudView& view, int width, int height, int frames, double turn_deg = 0.5);
  VolumetricClouds& clouds();
  // Compiles the multiple-scattering estimate with these coefficients (light_model_fit.glsl's define
  // names) instead of the committed fit; empty: the committed fit again.
  void set_light_model_fit(const std::map<std::string, double>& coefficients);

 private:
  void aim(const CloudView& view);
  double march_middle_pixel(const CloudView& view);
  template <typename Render>
  auto under_light(const Render& render);
  reference::Lighting reference_lighting(const glm::dvec3& planet_center_m, double planet_radius_m) const;
  Light light_ = Light::sun;
  struct ReferenceScene;
  // The field, medium and phase of the frame just rendered.
  std::unique_ptr<ReferenceScene> reference_scene();
  std::unique_ptr<World> world_;
  std::unique_ptr<Renderer> renderer_;
  glm::dvec3 sun_direction_;
  uint64_t frame_ = 0;
  DiskCache cache_;
};

}  // namespace welkin::clouds
