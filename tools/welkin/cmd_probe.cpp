// welkin probe [--scene FILE | --preset NAME] [--altitude-km A] [--view-zenith D] [--view-azimuth D]
//              [--sun-zenith D] [--sun-azimuth D] [--samples N] [--no-path-trace] [--json]
// One camera, one view ray, one sun (reference/probe.h geometry): the GPU path's transmittance and
// radiance next to the double-precision CPU reference (quadrature for single scattering, path
// tracing for all orders), with relative errors and run times. Radiance is for a sun of 1 lux.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "reference/path_tracer.h"
#include "reference/probe.h"
#include "reference/ray_geometry.h"
#include "session.h"
#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/atmosphere/lut_mapping.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

void add_probe_command(CLI::App& app, int& exit_code);

namespace {

using nlohmann::json;
namespace ref = welkin::atmosphere::reference;

struct ProbeOptions {
  std::string scene, preset;
  double altitude_km = 0.0, view_zenith = 80.0, view_azimuth = 0.0, sun_zenith = 60.0, sun_azimuth = 0.0;
  uint64_t samples = 1u << 16;
  bool no_path_trace = false;
  bool json = false;
};

// The atmosphere.Atmosphere object of a scene file, a preset, or {} (the defaults: Earth).
json atmosphere_json(World& world, const ProbeOptions& o) {
  if (!o.scene.empty()) {
    json doc = read_json_file(o.scene);
    if (doc.contains("entities") && doc["entities"].is_array())
      for (const auto& e : doc["entities"])
        if (e.contains("components") && e["components"].contains("atmosphere.Atmosphere"))
          return e["components"]["atmosphere.Atmosphere"];
    throw Error(ErrorInfo{.file = o.scene,
                          .path = "/entities",
                          .expected = "an entity with atmosphere.Atmosphere",
                          .found = "none"});
  }
  if (!o.preset.empty()) {
    world.modules().require_component("atmosphere.Atmosphere");
    const ModuleManifest* m = world.modules().manifest("atmosphere");
    auto file = m->data_dir / "presets" / (o.preset + ".json");
    if (!std::filesystem::is_regular_file(file))
      throw Error(ErrorInfo{.path = "--preset",
                            .expected = "a preset in " + (m->data_dir / "presets").string(),
                            .found = "'" + o.preset + "'"});
    return read_json_file(file.string());
  }
  return json::object();
}

ref::DensityProfile to_reference(const atmosphere::DensityProfile& p) {
  ref::DensityProfile out;
  auto conv = [](const atmosphere::DensityLayer& l) {
    return ref::DensityLayer{l.width_km, l.exp_term, l.exp_scale_per_km, l.linear_term_per_km,
                             l.constant_term};
  };
  if (p.size() == 1) out.layers[1] = conv(p[0]);
  if (p.size() >= 2) out.layers[0] = conv(p[0]), out.layers[1] = conv(p[1]);
  return out;
}

ref::AtmosphereModel to_reference(const atmosphere::Atmosphere& a) {
  ref::AtmosphereModel m;
  m.bottom_radius_km = a.bottom_radius_km;
  m.top_radius_km = a.top_radius_km;
  m.rayleigh_scattering = glm::dvec3(a.rayleigh_scattering);
  m.rayleigh_density = to_reference(a.rayleigh_density);
  m.mie_scattering = glm::dvec3(a.mie_scattering);
  m.mie_extinction = glm::dvec3(a.mie_extinction);
  m.mie_density = to_reference(a.mie_density);
  m.mie_phase = a.mie_phase == atmosphere::MiePhase::cornette_shanks ? ref::MiePhase::cornette_shanks
                                                                     : ref::MiePhase::henyey_greenstein;
  m.mie_g = a.mie_g;
  m.absorption_extinction = glm::dvec3(a.absorption_extinction);
  m.absorption_density = to_reference(a.absorption_density);
  m.ground_albedo = glm::dvec3(a.ground_albedo);
  return m;
}

// Bilinear lookup of the read-back transmittance LUT, as the shader's texture() does.
glm::dvec3 sample_transmittance(const ImageF& lut, const atmosphere::Atmosphere& a, double r, double mu) {
  double b = a.bottom_radius_km, t = a.top_radius_km;
  double H = std::sqrt(t * t - b * b), rho = std::sqrt(std::max(0.0, r * r - b * b));
  double d = std::max(0.0, -r * mu + std::sqrt(std::max(0.0, r * r * (mu * mu - 1.0) + t * t)));
  double d_min = t - r, d_max = rho + H;
  double x_mu = d_max > d_min ? std::clamp((d - d_min) / (d_max - d_min), 0.0, 1.0) : 0.0;
  double u = atmosphere::unit_to_sub_uv(x_mu, lut.width),
         v = atmosphere::unit_to_sub_uv(std::clamp(rho / H, 0.0, 1.0), lut.height);
  double fx = std::clamp(u * lut.width - 0.5, 0.0, lut.width - 1.0),
         fy = std::clamp(v * lut.height - 0.5, 0.0, lut.height - 1.0);
  int x0 = int(fx), y0 = int(fy), x1 = std::min(x0 + 1, lut.width - 1), y1 = std::min(y0 + 1, lut.height - 1);
  double wx = fx - x0, wy = fy - y0;
  auto at = [&](int x, int y) {  // readback rows run top to bottom
    const float* p = lut.pixel(x, lut.height - 1 - y);
    return glm::dvec3(p[0], p[1], p[2]);
  };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), wx), glm::mix(at(x0, y1), at(x1, y1), wx), wy);
}

struct GpuProbe {
  glm::dvec3 radiance{0.0}, transmittance{1.0};
  double gpu_ms = 0.0;   // atmosphere passes of a steady frame (LUTs cached), 1x1 pixel
  double wall_ms = 0.0;  // everything: world, shaders, two frames, readback
};

// Renders a 1x1 frame looking along the probe ray; LUTs are built in the same frame.
GpuProbe probe_gpu(const json& atmosphere, const ProbeOptions& o, bool single_only) {
  auto start = std::chrono::steady_clock::now();
  auto world = make_world();
  json atm = atmosphere;
  if (single_only) atm["multiple_scattering_factor"] = 0, atm["ground_albedo"] = {0, 0, 0};
  json camera = {{"position_m", {0, 0, o.altitude_km * 1000.0}},
                 {"heading_deg", std::remainder(90.0 - o.view_azimuth, 360.0)},
                 {"pitch_deg", 90.0 - o.view_zenith},
                 {"vertical_fov_deg", 1.0},
                 {"near_m", 1.0}};
  json sun = {{"azimuth_deg", std::remainder(90.0 - o.sun_azimuth, 360.0)},
              {"elevation_deg", 90.0 - o.sun_zenith},
              {"illuminance_lux", 1.0},
              {"color", {1, 1, 1}},
              {"visible_fraction", 1.0},
              {"disc", false}};
  json doc = {{"welkin_scene", 1},
              {"entities",
               {{{"name", "probe"},
                 {"components",
                  {{"core.Camera", camera}, {"atmosphere.Atmosphere", atm}, {"atmosphere.Sun", sun}}}}}}};
  load_scene(*world, doc, "probe");
  Renderer renderer(*world);
  // Frame 0 compiles shaders and builds the LUTs; frame 1 costs what every later frame costs.
  renderer.render_frame(FrameInfo{}, 1, 1);
  FrameResult frame = renderer.render_frame(FrameInfo{.index = 1}, 1, 1);
  GpuProbe g;
  for (const auto& t : frame.timings)
    if (t.name.rfind("atmosphere.", 0) == 0) g.gpu_ms += t.gpu_ms;
  ImageF hdr = renderer.read_hdr();
  g.radiance = glm::dvec3(hdr.rgba[0], hdr.rgba[1], hdr.rgba[2]);

  Registry& reg = world->registry();
  const auto& a = *reg.get<atmosphere::Atmosphere>(reg.first<atmosphere::Atmosphere>());
  const ImageF lut = read_texture_float(*world->resource<atmosphere::AtmosphereGpu>().transmittance);
  const ref::ProbeRay ray = ref::probe_ray(
      to_reference(a),
      {.altitude_km = o.altitude_km, .view_zenith_deg = o.view_zenith, .view_azimuth_deg = o.view_azimuth});
  double r = ray.camera_km.z, mu = ray.view_dir.z;
  if (r > a.top_radius_km) {  // from space: transmittance from where the ray enters the air
    double disc = r * r * (mu * mu - 1.0) + a.top_radius_km * a.top_radius_km;
    if (disc < 0.0 || mu >= 0.0) return g;  // misses the air: nothing in the way
    double s = -r * mu - std::sqrt(disc);
    double r_entry = a.top_radius_km;
    mu = (r * mu + s) / r_entry;
    r = r_entry;
  }
  if (ref::ray_hits_sphere_below(a.bottom_radius_km, r, mu)) {
    // Bruneton: T(camera -> ground) = T(ground, upwards) / T(camera, upwards along the reversed ray).
    double d =
        -r * mu - std::sqrt(std::max(0.0, r * r * (mu * mu - 1.0) + a.bottom_radius_km * a.bottom_radius_km));
    double r_g = a.bottom_radius_km, mu_g = (r * mu + d) / r_g;
    g.transmittance = glm::min(sample_transmittance(lut, a, r_g, -mu_g) /
                                   glm::max(sample_transmittance(lut, a, r, -mu), glm::dvec3(1e-30)),
                               glm::dvec3(1.0));
  } else {
    g.transmittance = sample_transmittance(lut, a, r, mu);
  }
  g.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return g;
}

json rgb(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }
json rgb(const double v[3]) { return json::array({v[0], v[1], v[2]}); }
glm::dvec3 vec(const double v[3]) { return {v[0], v[1], v[2]}; }

double max_rel(const glm::dvec3& a, const glm::dvec3& b) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), 1e-30));
  return e;
}

int run_probe(const ProbeOptions& o) {
  if (!o.scene.empty() && !o.preset.empty())
    throw Error(ErrorInfo{.path = "--preset", .expected = "either --scene or --preset", .found = "both"});
  // Declared first: the worlds' GL objects must go while the context lives.
  auto context = create_headless_context();
  auto world = make_world();
  json atm = atmosphere_json(*world, o);

  GpuProbe single = probe_gpu(atm, o, true), full = probe_gpu(atm, o, false);
  // The model the GPU used, as loaded and validated by the module.
  world = make_world();
  load_scene(*world,
             {{"welkin_scene", 1},
              {"entities", {{{"name", "a"}, {"components", {{"atmosphere.Atmosphere", atm}}}}}}},
             "probe");
  Registry& reg = world->registry();
  const ref::AtmosphereModel model =
      to_reference(*reg.get<atmosphere::Atmosphere>(reg.first<atmosphere::Atmosphere>()));
  const ref::ProbeGeometry geometry{.altitude_km = o.altitude_km,
                                    .view_zenith_deg = o.view_zenith,
                                    .view_azimuth_deg = o.view_azimuth,
                                    .sun_zenith_deg = o.sun_zenith,
                                    .sun_azimuth_deg = o.sun_azimuth};
  const ref::ProbeResult quad = ref::probe_quadrature(model, geometry);
  ref::ProbeResult traced;
  if (!o.no_path_trace) {
    const ref::ProbeRay ray = ref::probe_ray(model, geometry);
    // The GPU sky includes the lit ground where the ray meets it; so must the all-orders reference.
    ref::PathTraceSettings s{.samples = o.samples,
                             .camera_sees_ground = ref::ray_hits_sphere_below(
                                 model.bottom_radius_km, ray.camera_km.z, ray.view_dir.z)};
    traced = ref::probe_path_traced(model, geometry, s);
  }

  if (o.json) {
    json j{{"geometry",
            {{"altitude_km", o.altitude_km},
             {"view_zenith_deg", o.view_zenith},
             {"view_azimuth_deg", o.view_azimuth},
             {"sun_zenith_deg", o.sun_zenith},
             {"sun_azimuth_deg", o.sun_azimuth}}},
           {"transmittance",
            {{"gpu", rgb(full.transmittance)},
             {"reference", rgb(quad.transmittance)},
             {"max_relative_error", max_rel(full.transmittance, vec(quad.transmittance))}}},
           {"single_scattering",
            {{"gpu", rgb(single.radiance)},
             {"reference", rgb(quad.radiance)},
             {"reference_error_estimate", rgb(quad.radiance_ci95)},
             {"max_relative_error", max_rel(single.radiance, vec(quad.radiance))},
             {"gpu_ms", single.gpu_ms},
             {"gpu_wall_ms", single.wall_ms},
             {"reference_ms", quad.wall_ms}}},
           {"units", "radiance in cd/m^2 per lux of sun (1/sr)"}};
    json all{{"gpu", rgb(full.radiance)}, {"gpu_ms", full.gpu_ms}, {"gpu_wall_ms", full.wall_ms}};
    if (!o.no_path_trace)
      all.update({{"reference", rgb(traced.radiance)},
                  {"reference_ci95", rgb(traced.radiance_ci95)},
                  {"samples", traced.samples},
                  {"max_relative_error", max_rel(full.radiance, vec(traced.radiance))},
                  {"reference_ms", traced.wall_ms}});
    j["all_orders"] = all;
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  auto row = [](const char* what, const glm::dvec3& v, const char* extra) {
    std::printf("%-34s %12.6g %12.6g %12.6g  %s\n", what, v.x, v.y, v.z, extra);
  };
  char buf[160];
  std::printf(
      "probe: altitude %.6g km, view zenith %.6g deg azimuth %.6g deg, sun zenith %.6g deg azimuth %.6g "
      "deg\n",
      o.altitude_km, o.view_zenith, o.view_azimuth, o.sun_zenith, o.sun_azimuth);
  std::printf("%-34s %12s %12s %12s\n", "", "R", "G", "B");
  row("transmittance  gpu (LUT)", full.transmittance, "");
  std::snprintf(buf, sizeof buf, "max rel. error %.3g", max_rel(full.transmittance, vec(quad.transmittance)));
  row("transmittance  reference", vec(quad.transmittance), buf);
  std::snprintf(buf, sizeof buf, "%.2f ms GPU/frame, %.0f ms wall", single.gpu_ms, single.wall_ms);
  row("single scattering  gpu", single.radiance, buf);
  std::snprintf(buf, sizeof buf, "%.0f ms; max rel. error %.3g", quad.wall_ms,
                max_rel(single.radiance, vec(quad.radiance)));
  row("single scattering  quadrature", vec(quad.radiance), buf);
  std::snprintf(buf, sizeof buf, "%.2f ms GPU/frame, %.0f ms wall", full.gpu_ms, full.wall_ms);
  row("all orders  gpu (Hillaire)", full.radiance, buf);
  if (!o.no_path_trace) {
    std::snprintf(buf, sizeof buf, "%llu paths, %.0f ms; max rel. error %.3g",
                  (unsigned long long)traced.samples, traced.wall_ms,
                  max_rel(full.radiance, vec(traced.radiance)));
    row("all orders  path traced", vec(traced.radiance), buf);
    row("  95% confidence half-width", vec(traced.radiance_ci95), "");
  }
  std::printf("radiance in cd/m^2 per lux of sun (1/sr)\n");
  return kOk;
}

}  // namespace

void add_probe_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* cmd =
      app.add_subcommand("probe", "One view ray: GPU atmosphere against the CPU reference (error and time)");
  cmd->add_option("--scene", o->scene, "Take atmosphere.Atmosphere from this scene file")
      ->check(CLI::ExistingFile);
  cmd->add_option("--preset", o->preset,
                  "Take the atmosphere from a preset of the atmosphere module (earth, mars, ...)");
  cmd->add_option("--altitude-km", o->altitude_km, "Camera altitude above the ground")
      ->check(CLI::Range(-1e6, 1e7))
      ->capture_default_str();
  cmd->add_option("--view-zenith", o->view_zenith, "View zenith angle, degrees")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--view-azimuth", o->view_azimuth, "View azimuth, degrees from x towards y")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  cmd->add_option("--sun-zenith", o->sun_zenith, "Sun zenith angle, degrees")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--sun-azimuth", o->sun_azimuth, "Sun azimuth, degrees from x towards y")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  cmd->add_option("--samples", o->samples, "Paths for the all-orders reference")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32))
      ->capture_default_str();
  cmd->add_flag("--no-path-trace", o->no_path_trace, "Skip the (slow) all-orders reference");
  cmd->add_flag("--json", o->json, "Machine-readable output");
  cmd->callback([o, &exit_code] { exit_code = run_probe(*o); });
}

}  // namespace welkin::cli
