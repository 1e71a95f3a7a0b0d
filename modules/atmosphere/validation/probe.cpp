#include "validation/probe.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "reference/path_tracer.h"
#include "reference/ray_geometry.h"
#include "reference/transmittance.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
}

namespace welkin::atmosphere {

namespace {

namespace ref = reference;

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

glm::dvec3 vec(const double v[3]) {
  return {v[0], v[1], v[2]};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Light of the sun reflected once by the ground where the ray ends there (Lambertian, lit through
// the air above it), seen through the air in between.
glm::dvec3 lit_ground(const ref::AtmosphereModel& model, const ref::ProbeRay& ray) {
  const double r = ray.camera_km.z, mu = ray.view_dir.z;
  const ref::RayInterval iv = ref::atmosphere_interval(model, r, mu);
  if (!iv.intersects || !iv.hits_ground) return glm::dvec3(0.0);
  const glm::dvec3 ground = glm::normalize(ray.camera_km + iv.end_km * ray.view_dir);
  const double cos_sun = glm::dot(ground, ray.sun_dir);
  if (cos_sun <= 0.0) return glm::dvec3(0.0);
  return ref::transmittance_between(model, r, mu, iv.end_km) * model.ground_albedo * (cos_sun / ref::kPi) *
         ref::transmittance_to_sun(model, model.bottom_radius_km, cos_sun);
}

}  // namespace

std::optional<ProbeMethod> parse_probe_method(std::string_view name) {
  for (ProbeMethod m :
       {ProbeMethod::reference, ProbeMethod::pathtrace, ProbeMethod::lut, ProbeMethod::raymarch})
    if (name == probe_method_name(m)) return m;
  return std::nullopt;
}

const char* probe_method_name(ProbeMethod method) {
  switch (method) {
    case ProbeMethod::reference:
      return "reference";
    case ProbeMethod::pathtrace:
      return "pathtrace";
    case ProbeMethod::lut:
      return "lut";
    case ProbeMethod::raymarch:
      return "raymarch";
  }
  return "?";
}

ProbeValue probe_reference(const ref::AtmosphereModel& model, const ref::ProbeGeometry& g) {
  const auto start = std::chrono::steady_clock::now();
  const ref::ProbeResult q = ref::probe_quadrature(model, g);
  ProbeValue v;
  v.transmittance = vec(q.transmittance);
  v.radiance = vec(q.radiance) + lit_ground(model, ref::probe_ray(model, g));
  v.radiance_ci95 = vec(q.radiance_ci95);
  v.ms = elapsed_ms(start);
  return v;
}

ProbeValue probe_pathtrace(const ref::AtmosphereModel& model, const ref::ProbeGeometry& g,
                           bool single_scattering, const PathTraceOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const ref::PathTraceSettings s{.samples = o.samples,
                                 .seed = o.seed,
                                 .max_order = single_scattering ? 1 : 1000,
                                 .threads = o.threads,
                                 .camera_sees_ground = true};
  const ref::ProbeResult p = ref::probe_path_traced(model, g, s);
  ProbeValue v;
  v.transmittance = vec(p.transmittance);
  v.radiance = vec(p.radiance);
  v.radiance_ci95 = vec(p.radiance_ci95);
  v.samples = p.samples;
  v.ms = elapsed_ms(start);
  return v;
}

GpuProbe::GpuProbe(const Atmosphere& atmosphere, SkyMethod method, bool single_scattering) : method_(method) {
  nlohmann::json atm = object_to_json(type_desc<Atmosphere>(), &atmosphere);
  atm["method"] = method == SkyMethod::raymarch ? "raymarch" : "lut";
  // The probe's camera is placed by altitude above the ground straight below the origin.
  atm["planet_center_below_origin"] = true;
  if (single_scattering) atm["multiple_scattering_factor"] = 0.0;
  const nlohmann::json sun = {
      {"illuminance_lux", 1.0}, {"color", {1, 1, 1}}, {"visible_fraction", 1.0}, {"disc", false}};
  const nlohmann::json camera = {{"vertical_fov_deg", 1.0}, {"near_m", 1.0}};
  const nlohmann::json doc = {
      {"welkin_scene", 1},
      {"entities",
       {{{"name", "probe"},
         {"components",
          {{"core.Camera", camera}, {"atmosphere.Atmosphere", atm}, {"atmosphere.Sun", sun}}}}}}};
  world_ = std::make_unique<World>();
  world_->modules().add_static(welkin::modules::atmosphere_module());
  load_scene(*world_, doc, "probe");
  renderer_ = std::make_unique<Renderer>(*world_);
  renderer_->set_full_precision(true);  // twilight radiance is below half floats' normal range
}

GpuProbe::~GpuProbe() = default;

const Atmosphere& GpuProbe::atmosphere() const {
  Registry& reg = world_->registry();
  return *reg.get<Atmosphere>(reg.first<Atmosphere>());
}

void GpuProbe::aim(const ref::ProbeGeometry& g) {
  // Probe azimuths run from x (east) towards y (north); scene headings clockwise from north.
  Registry& reg = world_->registry();
  Camera& cam = *reg.get<Camera>(reg.first<Camera>());
  cam.position_m = glm::dvec3(0.0, 0.0, g.altitude_km * 1000.0);
  cam.heading_deg = float(std::remainder(90.0 - g.view_azimuth_deg, 360.0));
  cam.pitch_deg = float(90.0 - g.view_zenith_deg);
  Sun& sun = *reg.get<Sun>(reg.first<Sun>());
  sun.azimuth_deg = float(std::remainder(90.0 - g.sun_azimuth_deg, 360.0));
  sun.elevation_deg = float(90.0 - g.sun_zenith_deg);
}

ProbeValue GpuProbe::evaluate(const ref::ProbeGeometry& g) {
  aim(g);
  renderer_->render_frame(FrameInfo{.index = frame_++}, 1, 1);
  const ImageF hdr = renderer_->read_hdr();
  ProbeValue v;
  v.radiance = glm::dvec3(hdr.rgba[0], hdr.rgba[1], hdr.rgba[2]);

  // Transmittance by the method's own functions, with this frame's uniforms and LUTs still bound.
  RenderContext& rc = world_->resource<RenderContext>();
  AtmosphereGpu& gpu = world_->resource<AtmosphereGpu>();
  Texture out(TextureDesc{.width = 1, .height = 1, .format = TextureFormat::rgba32f, .linear_filter = false});
  bind_for_materials(gpu);
  glBindImageTexture(0, out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  const Program& p = rc.shaders.compute(
      "atmosphere/probe_transmittance.comp",
      {{"ATM_SKY_MODE", method_ == SkyMethod::raymarch ? "2" : "0"}, {"ATM_MOON_LIGHT", "0"}});
  p.set("u_direction", glm::vec3(rc.view.forward));
  p.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  const ImageF t = read_texture_float(out);
  v.transmittance = glm::dvec3(t.rgba[0], t.rgba[1], t.rgba[2]);
  return v;
}

FrameCost GpuProbe::frame_cost(const ref::ProbeGeometry& g, int width, int height, int frames) {
  aim(g);
  for (int i = 0; i < 2; ++i) renderer_->render_frame(FrameInfo{.index = frame_++}, width, height);
  std::vector<double> atmosphere, sky, frame;
  for (int i = 0; i < frames; ++i) {
    FrameResult r;
    world_->resource<AtmosphereGpu>().forget_per_frame_luts();  // the cost of a moving view
    frame.push_back(
        finished_ms([&] { r = renderer_->render_frame(FrameInfo{.index = frame_++}, width, height); }));
    double a = 0.0, s = 0.0;
    for (const PassTiming& t : r.timings) {
      if (t.name.rfind("atmosphere.", 0) == 0) a += t.gpu_ms;
      if (t.name == "atmosphere.sky") s += t.gpu_ms;
    }
    atmosphere.push_back(a);
    sky.push_back(s);
  }
  FrameCost c{.width = width, .height = height};
  c.atmosphere_ms = median(atmosphere);
  c.sky_ms = median(sky);
  c.frame_ms = median(frame);
  c.copy_ms = fullscreen_copy_floor_ms(world_->resource<RenderContext>().shaders, width, height);
  return c;
}

}  // namespace welkin::atmosphere
