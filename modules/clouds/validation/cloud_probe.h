#pragma once
// The GPU march against the CPU reference on single view rays through the same cloud field: a world
// with the clouds, a white sun (core.DirectionalLight, 100 klx, no sky light, no air, no ground
// bounce) so that both see exactly the same light, and a 1x1 frame aimed along each ray.
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>

#include "reference/cloud_path_tracer.h"
#include "welkin/clouds/components.h"
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
  // Requires a current GL 4.5 context. The clouds' temporal upscaling is turned off: one frame, one ray.
  CloudProbe(const VolumetricClouds& clouds, double sun_azimuth_deg, double sun_elevation_deg);
  ~CloudProbe();
  static constexpr double kSunIlluminance = 100000.0;

  // Radiance (cd/m^2, green channel) of the ray through the centre of a 1x1 frame.
  double gpu_radiance(const CloudView& view);
  // The path-traced radiance of the same ray through the same field (the noise read back).
  reference::CloudRadianceEstimate reference_radiance(const CloudView& view,
                                                      const reference::PathTraceSettings& settings);
  // Median GPU milliseconds of the clouds' passes per frame of width x height, and of a copy.
  struct Cost {
    double clouds_ms = 0.0, copy_ms = 0.0;
  };
  // The frame `camera` sees (its position, heading, pitch, roll and field of view), width x height,
  // row by row from the top: the radiance (green) marched with the probe's clouds, and path traced
  // through the same field (settings.samples paths per pixel; pixels shared among settings.threads
  // workers, each pixel its own seed, so the image does not depend on the thread count).
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
  struct ReferenceScene;
  // The field, medium and phase of the frame just rendered.
  std::unique_ptr<ReferenceScene> reference_scene();
  std::unique_ptr<World> world_;
  std::unique_ptr<Renderer> renderer_;
  glm::dvec3 sun_direction_;
  uint64_t frame_ = 0;
};

}  // namespace welkin::clouds
