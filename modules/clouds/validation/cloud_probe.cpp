#include "cloud_probe.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>
#include <type_traits>

#include "cloud_field.h"
#include "clouds_gpu.h"
#include "reference/medium.h"
#include "reference/phase.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& clouds_module();
}

namespace welkin::clouds {

namespace ref = reference;

namespace {

// The cloud field as the reference's medium: extinction from the field, the layers' shell as the
// only stretch where it may be non-zero (cut at the ground), the sum of full densities its bound.
class CloudMedium final : public ref::Medium {
 public:
  explicit CloudMedium(const CloudField& field) : field_(field) {
    const FrameBlock& f = field.frame();
    center_ = -glm::dvec3(f.up) * double(f.camera_radius_m);
    radius_ = f.planet_radius_m;
  }
  double extinction(const glm::dvec3& p) const override { return field_.extinction(p); }
  const glm::dvec3& planet_center_m() const { return center_; }
  double planet_radius_m() const { return radius_; }
  ref::MajorantSegments segments(const ref::Ray& ray) const override {
    ref::MajorantSegments s = ref::spherical_shell_segments(ray, center_, radius_ + field_.lowest_m(),
                                                            radius_ + field_.highest_m(), field_.majorant());
    double t0, t1;
    if (ref::intersect_sphere(ray, center_, radius_, t0, t1) && t0 > 0.0) {
      ref::MajorantSegments cut;
      for (ref::MajorantSegment g : s)
        if (g.t0 < t0) g.t1 = std::min(g.t1, t0), cut.push_back(g);
      return cut;
    }
    return s;
  }

 private:
  const CloudField& field_;
  glm::dvec3 center_;
  double radius_;
};

}  // namespace

CloudProbe::CloudProbe(const VolumetricClouds& clouds, double sun_azimuth_deg, double sun_elevation_deg) {
  world_ = std::make_unique<World>();
  world_->modules().add_static(welkin::modules::clouds_module());
  VolumetricClouds c = clouds;
  c.temporal_upscaling = false;
  c.ground_albedo = 0.0f;
  const nlohmann::json doc = {
      {"welkin_scene", 1},
      {"entities",
       {{{"name", "camera"}, {"components", {{"core.Camera", {{"vertical_fov_deg", 1.0}}}}}},
        {{"name", "sun"},
         {"components",
          {{"core.DirectionalLight",
            {{"azimuth_deg", sun_azimuth_deg},
             {"elevation_deg", sun_elevation_deg},
             {"color", {1, 1, 1}},
             {"illuminance_lux", kSunIlluminance},
             {"ambient_fraction", 0.0}}}}}},
        {{"name", "clouds"},
         {"components", {{"clouds.VolumetricClouds", object_to_json(type_desc<VolumetricClouds>(), &c)}}}}}}};
  load_scene(*world_, doc, "cloud probe");
  renderer_ = std::make_unique<Renderer>(*world_);
  sun_direction_ = direction_from_azimuth_elevation(sun_azimuth_deg, sun_elevation_deg);
}

CloudProbe::~CloudProbe() = default;

void CloudProbe::set_light_model_fit(const std::map<std::string, double>& coefficients) {
  std::map<std::string, std::string>& fit = world_->resource<CloudsGpu>().light_model_fit;
  fit.clear();
  char text[32];
  for (const auto& [name, value] : coefficients) {
    std::snprintf(text, sizeof text, "%.9g", value);
    fit[name] = std::string(text) + (std::string(text).find_first_of(".e") == std::string::npos ? ".0" : "");
  }
}

VolumetricClouds& CloudProbe::clouds() {
  Registry& reg = world_->registry();
  return *reg.get<VolumetricClouds>(reg.first<VolumetricClouds>());
}

void CloudProbe::aim(const CloudView& view) {
  Registry& reg = world_->registry();
  Camera& cam = *reg.get<Camera>(reg.first<Camera>());
  cam.position_m = {view.east_m, view.north_m, view.altitude_m};
  cam.heading_deg = float(view.heading_deg);
  cam.pitch_deg = float(view.pitch_deg);
}

double CloudProbe::march_middle_pixel(const CloudView& view) {
  aim(view);
  double sum = 0.0;
  for (int i = 0; i < kJitterFrames; ++i) {
    renderer_->render_frame(FrameInfo{.index = frame_++}, 1, kRows);
    sum += renderer_->read_hdr().pixel(0, kRows / 2)[1];
  }
  return sum / kJitterFrames;
}

// The march under the probe's light: `render` marched once under the sun, or (the sky alone) with
// and without the sky, the difference taken value by value. The two frames have the same index, so
// the same jitter: the sun's light is the same in both to the bit.
template <typename Render>
auto CloudProbe::under_light(const Render& render) {
  const uint64_t frame = frame_;
  auto result = render();
  if (light_ == Light::sun) return result;
  Registry& reg = world_->registry();
  DirectionalLight& sun = *reg.get<DirectionalLight>(reg.first<DirectionalLight>());
  sun.ambient_fraction = float(kSkyFraction);
  frame_ = frame;
  auto with_sky = render();
  sun.ambient_fraction = 0.0f;
  if constexpr (std::is_same_v<decltype(result), double>) {
    return with_sky - result;
  } else {
    for (size_t i = 0; i < result.size(); ++i) result[i] = with_sky[i] - result[i];
    return result;
  }
}

double CloudProbe::gpu_radiance(const CloudView& view) {
  return under_light([&] { return march_middle_pixel(view); });
}

ref::Lighting CloudProbe::reference_lighting(const glm::dvec3& planet_center_m,
                                             double planet_radius_m) const {
  if (light_ == Light::sun)
    return {.sun_direction = sun_direction_, .sun_irradiance = kSunIlluminance};
  return {.sun_direction = sun_direction_,
          .sun_irradiance = 0.0,
          .sky_radiance = kSkyFraction * kSunIlluminance / M_PI,
          .planet_center_m = planet_center_m,
          .planet_radius_m = planet_radius_m};
}

struct CloudProbe::ReferenceScene {
  CloudField field;
  CloudMedium medium;
  std::unique_ptr<ref::PhaseFunction> phase;
  ReferenceScene(CloudField f, const VolumetricClouds& c) : field(std::move(f)), medium(field) {
    if (c.phase == PhaseModel::droplet_mie)
      phase = std::make_unique<ref::ApproximateMie>(c.droplet_diameter_um);
    else
      phase = std::make_unique<ref::DualLobeHenyeyGreenstein>(c.phase_g_forward, c.phase_g_backward,
                                                              1.0 - c.phase_mix);
    medium.single_scattering_albedo =
        c.scattering_coefficient /
        std::max(double(c.scattering_coefficient + c.absorption_coefficient), 1e-12);
  }
};

std::unique_ptr<CloudProbe::ReferenceScene> CloudProbe::reference_scene() {
  const CloudsGpu& gpu = world_->resource<CloudsGpu>();
  return std::make_unique<ReferenceScene>(CloudField(read_noise(gpu), gpu.block, gpu.layers), clouds());
}

namespace {

// What a cached reference ray depends on (reference_radiance): everything but the big inputs is
// written out; the noise, the layers and the field along the ray enter as hashes.
std::string reference_key(const VolumetricClouds& clouds, const CloudField& field, const ref::Medium& medium,
                          const NoiseVolumes& noise, const std::vector<LayerBlock>& layers,
                          const CloudView& view, const ref::Ray& ray, const glm::dvec3& sun,
                          const ref::PathTraceSettings& s) {
  uint64_t noise_hash = DiskCache::hash({});
  for (const std::vector<uint8_t>* v :
       {&noise.shape, &noise.detail, &noise.weather, &noise.systems, &noise.coverage_map})
    noise_hash =
        DiskCache::hash(std::string_view(reinterpret_cast<const char*>(v->data()), v->size()), noise_hash);
  const uint64_t layers_hash = DiskCache::hash(
      std::string_view(reinterpret_cast<const char*>(layers.data()), layers.size() * sizeof(LayerBlock)));
  // The field as the ray sees it: 1024 points spread over the stretches where it may be non-zero.
  double length = 0.0;
  const ref::MajorantSegments segments = medium.segments(ray);
  for (const ref::MajorantSegment& g : segments) length += g.t1 - g.t0;
  uint64_t field_hash = DiskCache::hash({});
  for (int i = 0; i < 1024 && length > 0.0; ++i) {
    double into = (i + 0.5) * length / 1024.0, t = 0.0;  // distance into the stretches, and along the ray
    for (const ref::MajorantSegment& g : segments) {
      t = g.t0 + into;
      if (into <= g.t1 - g.t0) break;
      into -= g.t1 - g.t0;
    }
    const double e = field.extinction(ray.origin + ray.direction * t);
    field_hash = DiskCache::hash(std::string_view(reinterpret_cast<const char*>(&e), sizeof e), field_hash);
  }
  char text[512];
  std::snprintf(text, sizeof text,
                "|sun %.17g %.17g %.17g|view %.17g %.17g %.17g %.17g %.17g|paths %llu seed %llu orders %d "
                "roulette %d batch %llu "
                "steps %llu|noise %016llx layers %016llx field %016llx",
                sun.x, sun.y, sun.z, view.east_m, view.north_m, view.altitude_m, view.heading_deg,
                view.pitch_deg, (unsigned long long)s.samples, (unsigned long long)s.seed, s.max_orders,
                s.roulette_start_order, (unsigned long long)s.batch_size,
                (unsigned long long)s.max_steps_per_path, (unsigned long long)noise_hash,
                (unsigned long long)layers_hash, (unsigned long long)field_hash);
  return "clouds reference ray v1|" + object_to_json(type_desc<VolumetricClouds>(), &clouds).dump() + text;
}

// A reference ray as the cache stores it.
struct StoredEstimate {
  double scattered[2], transmittance[2], background[2], mean_scattering_events, wall_ms;
  uint64_t samples, truncated_paths, majorant_violations;
};
StoredEstimate stored(const ref::CloudRadianceEstimate& r) {
  return {{r.scattered.mean, r.scattered.ci95},
          {r.transmittance.mean, r.transmittance.ci95},
          {r.background.mean, r.background.ci95},
          r.mean_scattering_events,
          r.wall_ms,
          r.samples,
          r.truncated_paths,
          r.majorant_violations};
}
ref::CloudRadianceEstimate estimate(const StoredEstimate& s) {
  ref::CloudRadianceEstimate r;
  r.scattered = {s.scattered[0], s.scattered[1]}, r.transmittance = {s.transmittance[0], s.transmittance[1]};
  r.background = {s.background[0], s.background[1]};
  r.samples = s.samples, r.mean_scattering_events = s.mean_scattering_events,
  r.truncated_paths = s.truncated_paths;
  r.majorant_violations = s.majorant_violations, r.wall_ms = s.wall_ms;
  return r;
}

}  // namespace

ref::CloudRadianceEstimate CloudProbe::reference_radiance(const CloudView& view,
                                                          const ref::PathTraceSettings& settings) {
  aim(view);
  renderer_->render_frame(FrameInfo{.index = frame_++}, 1, 1);  // this view's frame block and layers
  const CloudsGpu& gpu = world_->resource<CloudsGpu>();
  NoiseVolumes noise = read_noise(gpu);
  const ReferenceScene scene(CloudField(noise, gpu.block, gpu.layers), clouds());
  const glm::dvec3 dir = direction_from_azimuth_elevation(view.heading_deg, view.pitch_deg);
  const ref::Ray ray{glm::dvec3(0.0), dir};
  std::string key;
  if (cache_.enabled()) {
    key = reference_key(clouds(), scene.field, scene.medium, noise, gpu.layers, view, ray, sun_direction_,
                        settings);
    if (light_ == Light::sky) key += "|sky alone " + std::to_string(kSkyFraction);
    if (const auto bytes = cache_.read(key, sizeof(StoredEstimate))) {
      StoredEstimate s;
      std::memcpy(&s, bytes->data(), sizeof s);
      return estimate(s);
    }
  }
  const ref::CloudRadianceEstimate r = ref::path_trace(
      scene.medium, *scene.phase, ray,
      reference_lighting(scene.medium.planet_center_m(), scene.medium.planet_radius_m()), settings);
  if (cache_.enabled()) {
    const StoredEstimate s = stored(r);
    cache_.write(key, std::string_view(reinterpret_cast<const char*>(&s), sizeof s));
  }
  return r;
}

std::vector<double> CloudProbe::gpu_image(const Camera& camera, int width, int height) {
  Registry& reg = world_->registry();
  *reg.get<Camera>(reg.first<Camera>()) = camera;
  return under_light([&] {
    std::vector<double> image(size_t(width) * height, 0.0);
    for (int i = 0; i < kJitterFrames; ++i) {
      renderer_->render_frame(FrameInfo{.index = frame_++}, width, height);
      const ImageF hdr = renderer_->read_hdr();
      for (int y = 0; y < height; ++y)  // read_hdr's rows run from the top, as pixel_direction's
        for (int x = 0; x < width; ++x)
          image[size_t(y) * width + x] += hdr.pixel(x, y)[1] / kJitterFrames;
    }
    return image;
  });
}

std::vector<ref::CloudRadianceEstimate> CloudProbe::reference_image(const Camera& camera, int width,
                                                                    int height,
                                                                    const ref::PathTraceSettings& settings) {
  gpu_image(camera, width, height);  // this view's frame block and layers
  const std::unique_ptr<ReferenceScene> scene = reference_scene();
  const FrameView view = make_frame_view(camera, width, height);
  const ref::Lighting lighting =
      reference_lighting(scene->medium.planet_center_m(), scene->medium.planet_radius_m());
  std::vector<ref::CloudRadianceEstimate> image(size_t(width) * height);
  // Cached whole: the key hashes each pixel's ray key (its field along the ray included), so that a
  // change of the field that a pixel sees path traces the image again.
  std::string key;
  if (cache_.enabled()) {
    const CloudsGpu& gpu = world_->resource<CloudsGpu>();
    const NoiseVolumes noise = read_noise(gpu);
    const CloudView at{.name = "image",
                       .altitude_m = camera.position_m.z,
                       .heading_deg = camera.heading_deg,
                       .pitch_deg = camera.pitch_deg,
                       .east_m = camera.position_m.x,
                       .north_m = camera.position_m.y};
    uint64_t h = DiskCache::hash({});
    for (size_t i = 0; i < image.size(); ++i) {
      const glm::dvec3 dir =
          glm::normalize(glm::dvec3(pixel_direction(view, double(i % width) + 0.5, double(i / width) + 0.5)));
      ref::PathTraceSettings s = settings;
      s.seed = settings.seed + i;
      h = DiskCache::hash(reference_key(clouds(), scene->field, scene->medium, noise, gpu.layers, at,
                                        ref::Ray{glm::dvec3(0.0), dir}, sun_direction_, s),
                          h);
    }
    char text[96];
    std::snprintf(text, sizeof text, "clouds reference image v1|%dx%d fov %.9g|%016llx", width, height,
                  double(camera.vertical_fov_deg), (unsigned long long)h);
    key = text;
    if (const auto bytes = cache_.read(key, image.size() * sizeof(StoredEstimate))) {
      for (size_t i = 0; i < image.size(); ++i) {
        StoredEstimate s;
        std::memcpy(&s, bytes->data() + i * sizeof s, sizeof s);
        image[i] = estimate(s);
      }
      return image;
    }
  }
  std::atomic<size_t> next{0};
  auto worker = [&] {
    ref::PathTraceSettings s = settings;
    s.threads = 1;
    s.batch_size = std::max<std::uint64_t>(settings.samples, 1);
    for (size_t i = next++; i < image.size(); i = next++) {
      s.seed = settings.seed + i;
      const glm::dvec3 dir =
          glm::normalize(glm::dvec3(pixel_direction(view, double(i % width) + 0.5, double(i / width) + 0.5)));
      image[i] = ref::path_trace(scene->medium, *scene->phase, ref::Ray{glm::dvec3(0.0), dir}, lighting, s);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(settings.threads, 1); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (cache_.enabled()) {
    std::string bytes;
    for (const ref::CloudRadianceEstimate& r : image) {
      const StoredEstimate s = stored(r);
      bytes.append(reinterpret_cast<const char*>(&s), sizeof s);
    }
    cache_.write(key, bytes);
  }
  return image;
}

CloudProbe::Cost CloudProbe::cost(const CloudView& view, int width, int height, int frames, double turn_deg) {
  CloudView turning = view;
  aim(turning);
  for (int i = 0; i < 2; ++i) renderer_->render_frame(FrameInfo{.index = frame_++}, width, height);
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i) {
    turning.heading_deg += turn_deg;
    aim(turning);
    const FrameResult r = renderer_->render_frame(FrameInfo{.index = frame_++}, width, height);
    double sum = 0.0;
    for (const PassTiming& t : r.timings)
      if (t.name.rfind("clouds.", 0) == 0) sum += t.gpu_ms;
    ms.push_back(sum);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return {ms[ms.size() / 2], fullscreen_copy_floor_ms(renderer_->context().shaders, width, height)};
}

}  // namespace welkin::clouds
