// welkin probe [--scene FILE | --preset NAME] [--set FIELD=VALUE ...] [--altitude-km A]
//              [--view-zenith-deg VZ] [--view-azimuth-deg VA] [--sun-zenith-deg SZ] [--sun-azimuth-deg SA]
//              [--method reference|pathtrace|lut|raymarch|all] [--orders 1|all] [--samples N] [--seed S]
//              [--threads N] [--size WxH] [--json]
// One camera, one view ray, one sun (reference/probe.h geometry: z up, azimuths from x towards y for
// view and sun alike): transmittance and radiance of the ray by any method, so anyone can compare
// methods on the same ray; `--method all` puts them side by side with their relative errors.
// Radiance is for sun illuminance 1, atmosphere only (no sun disc, the ground lit as its albedo says
// where the ray meets it), in 1/sr. `--orders 1` is single scattering (for lut and raymarch the
// multiple-scattering LUT is switched off).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "session.h"
#include "validation/probe.h"
#include "validation/reference_model.h"
#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/presets.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

void add_probe_command(CLI::App& app, int& exit_code);

namespace {

using atmosphere::ProbeMethod;
using atmosphere::ProbeValue;
using nlohmann::json;
namespace ref = welkin::atmosphere::reference;

struct ProbeOptions {
  std::string scene, preset, method = "all", orders, size = "640x360";
  std::vector<std::string> sets;
  double altitude_km = 0.0, view_zenith = 80.0, view_azimuth = 0.0, sun_zenith = 60.0, sun_azimuth = 0.0;
  uint64_t samples = 1u << 16, seed = 1;
  int threads = 2;
  bool json = false;
};

// `--set module.field=value` names a field of whichever of the module's components has it; the
// full `module.Component/field=value` is passed through. Either way the runtime's field paths
// resolve, range-check and validate it, so the errors are the same as a scene file's.
std::string full_assignment(World& world, const std::string& assignment) {
  const auto eq = assignment.find('='), slash = assignment.find('/'), dot = assignment.find('.');
  if (eq == std::string::npos || (slash != std::string::npos && slash < eq) || dot == std::string::npos ||
      dot > eq)
    return assignment;
  const std::string module = assignment.substr(0, dot);
  const std::string path = assignment.substr(dot + 1, eq - dot - 1);
  const std::string field = path.substr(0, path.find('/'));
  const ModuleManifest* m = world.modules().manifest(module);
  if (!m || m->components.empty()) return assignment;  // apply_assignment names what is wrong
  for (const std::string& component : m->components) {
    const ComponentInfo& info = world.modules().require_component(component);
    if (info.type->field(field)) return component + "/" + path + assignment.substr(eq);
  }
  // No component has it: let the first report the unknown field with the list of its fields.
  return m->components.front() + "/" + path + assignment.substr(eq);
}

// The atmosphere the probe uses: from a scene, a preset or the defaults (Earth), then `--set`.
atmosphere::Atmosphere probe_atmosphere(const ProbeOptions& o) {
  auto world = make_world();
  Registry& reg = world->registry();
  if (!o.scene.empty()) {
    load_scene_file(*world, o.scene);
  } else {
    const ComponentInfo& info = world->modules().require_component("atmosphere.Atmosphere");
    atmosphere::Atmosphere a;
    if (!o.preset.empty()) {
      const ModuleManifest* m = world->modules().manifest("atmosphere");
      const auto file = atmosphere::preset_dir(m->data_dir) / (o.preset + ".json");
      if (!std::filesystem::is_regular_file(file))
        throw Error(ErrorInfo{.path = "--preset",
                              .expected = "a preset in " + atmosphere::preset_dir(m->data_dir).string(),
                              .found = "'" + o.preset + "'"});
      a = atmosphere::load_preset_file(file);
    }
    *static_cast<atmosphere::Atmosphere*>(reg.emplace(reg.create(), *info.type)) = a;
  }
  if (reg.first<atmosphere::Atmosphere>().is_null())
    throw Error(ErrorInfo{.file = o.scene,
                          .path = "/entities",
                          .expected = "an entity with atmosphere.Atmosphere",
                          .found = "none"});
  for (const std::string& s : o.sets) {
    const std::string full = full_assignment(*world, s);
    if (full.rfind("atmosphere.Atmosphere/", 0) != 0 && full.find('/') != std::string::npos &&
        full.find('/') < full.find('='))
      throw Error(
          ErrorInfo{.path = "--set " + s,
                    .expected = "a field of atmosphere.Atmosphere (the probe's sun comes from --sun-*)",
                    .found = "'" + full.substr(0, full.find('/')) + "'"});
    apply_assignment(*world, full);
  }
  return *reg.get<atmosphere::Atmosphere>(reg.first<atmosphere::Atmosphere>());
}

json rgb(const glm::dvec3& v) {
  return json::array({v.x, v.y, v.z});
}

double max_rel(const glm::dvec3& a, const glm::dvec3& b) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), 1e-30));
  return e;
}

struct Evaluated {
  ProbeMethod method;
  bool single = false;
  ProbeValue value;
  std::optional<atmosphere::FrameCost> cost;  // GPU methods: per frame at --size
};

Evaluated evaluate(ProbeMethod method, bool single, const atmosphere::Atmosphere& atm,
                   const ref::ProbeGeometry& g, const ProbeOptions& o, int width, int height) {
  Evaluated e{.method = method, .single = single};
  const ref::AtmosphereModel model = atmosphere::to_reference(atm);
  switch (method) {
    case ProbeMethod::reference:
      e.value = atmosphere::probe_reference(model, g);
      break;
    case ProbeMethod::pathtrace:
      std::fprintf(stderr, "path tracing %llu paths...\n", (unsigned long long)o.samples);
      e.value = atmosphere::probe_pathtrace(model, g, single,
                                            {.samples = o.samples, .seed = o.seed, .threads = o.threads});
      break;
    case ProbeMethod::lut:
    case ProbeMethod::raymarch: {
      atmosphere::GpuProbe probe(
          atm, method == ProbeMethod::raymarch ? atmosphere::SkyMethod::raymarch : atmosphere::SkyMethod::lut,
          single);
      e.value = probe.evaluate(g);
      e.cost = probe.frame_cost(g, width, height, 5);
      e.value.ms = e.cost->atmosphere_ms;
      break;
    }
  }
  return e;
}

json to_json(const Evaluated& e) {
  json j{{"method", atmosphere::probe_method_name(e.method)},
         {"orders", e.single ? json(1) : json("all")},
         {"transmittance", rgb(e.value.transmittance)},
         {"radiance", rgb(e.value.radiance)},
         {"ms", e.value.ms}};
  if (e.method == ProbeMethod::pathtrace) {
    j["radiance_ci95"] = rgb(e.value.radiance_ci95);
    j["samples"] = e.value.samples;
  }
  if (e.method == ProbeMethod::reference) j["radiance_error_estimate"] = rgb(e.value.radiance_ci95);
  if (e.cost) {
    j["ms_is"] = "GPU time of the atmosphere's passes per frame at frame_size (median, forced to completion)";
    j["frame_size"] = std::to_string(e.cost->width) + "x" + std::to_string(e.cost->height);
    j["sky_pass_ms"] = e.cost->sky_ms;
    j["frame_ms"] = e.cost->frame_ms;
    j["copy_ms"] = e.cost->copy_ms;
  } else {
    j["ms_is"] = "CPU wall time of this ray";
  }
  return j;
}

std::string cost_text(const Evaluated& e) {
  char buf[200];
  if (e.cost)
    std::snprintf(buf, sizeof buf, "%.2f ms GPU per %dx%d frame (sky pass %.2f ms, copy %.2f ms)", e.value.ms,
                  e.cost->width, e.cost->height, e.cost->sky_ms, e.cost->copy_ms);
  else if (e.method == ProbeMethod::pathtrace)
    std::snprintf(buf, sizeof buf, "%.0f ms CPU, %llu paths", e.value.ms,
                  (unsigned long long)e.value.samples);
  else
    std::snprintf(buf, sizeof buf, "%.1f ms CPU", e.value.ms);
  return buf;
}

int run_probe(const ProbeOptions& o) {
  if (!o.scene.empty() && !o.preset.empty())
    throw Error(ErrorInfo{.path = "--preset", .expected = "either --scene or --preset", .found = "both"});
  const bool all = o.method == "all";
  const std::optional<ProbeMethod> parsed = atmosphere::parse_probe_method(o.method);
  if (!all && !parsed)
    throw Error(ErrorInfo{.path = "--method",
                          .expected = "reference, pathtrace, lut, raymarch or all",
                          .found = "'" + o.method + "'"});
  if (!o.orders.empty() && o.orders != "1" && o.orders != "all")
    throw Error(ErrorInfo{.path = "--orders", .expected = "1 or all", .found = "'" + o.orders + "'"});
  // The quadrature is single scattering only; it is the default there, and asking for more is an error.
  const ProbeMethod method = parsed.value_or(ProbeMethod::lut);
  const bool is_reference = !all && method == ProbeMethod::reference;
  const bool single = o.orders == "1" || (o.orders.empty() && is_reference);
  if (is_reference && !single)
    throw Error(ErrorInfo{.path = "--orders",
                          .expected = "1 with --method reference (quadrature is single scattering; pathtrace "
                                      "gives all orders)",
                          .found = "'all'"});
  int width = 0, height = 0;
  parse_size(o.size, width, height);

  const atmosphere::Atmosphere atm = probe_atmosphere(o);
  const ref::ProbeGeometry g{.altitude_km = o.altitude_km,
                             .view_zenith_deg = o.view_zenith,
                             .view_azimuth_deg = o.view_azimuth,
                             .sun_zenith_deg = o.sun_zenith,
                             .sun_azimuth_deg = o.sun_azimuth};
  std::vector<ProbeMethod> methods;
  if (all) {
    // The baseline first: quadrature for single scattering, path tracing for all orders.
    methods = single ? std::vector{ProbeMethod::reference, ProbeMethod::pathtrace, ProbeMethod::lut,
                                   ProbeMethod::raymarch}
                     : std::vector{ProbeMethod::pathtrace, ProbeMethod::lut, ProbeMethod::raymarch};
  } else {
    methods = {method};
  }
  std::unique_ptr<GlContext> context;
  for (ProbeMethod m : methods)
    if (!context && (m == ProbeMethod::lut || m == ProbeMethod::raymarch))
      context = create_headless_context();
  std::vector<Evaluated> results;
  for (ProbeMethod m : methods) results.push_back(evaluate(m, single, atm, g, o, width, height));

  const json geometry{{"altitude_km", o.altitude_km},
                      {"view_zenith_deg", o.view_zenith},
                      {"view_azimuth_deg", o.view_azimuth},
                      {"sun_zenith_deg", o.sun_zenith},
                      {"sun_azimuth_deg", o.sun_azimuth}};
  if (o.json) {
    json j;
    if (!all) {
      j = to_json(results[0]);
    } else {
      json list = json::array();
      for (const Evaluated& e : results) {
        json m = to_json(e);
        m["radiance_max_relative_error"] = max_rel(e.value.radiance, results[0].value.radiance);
        m["transmittance_max_relative_error"] =
            max_rel(e.value.transmittance, results[0].value.transmittance);
        list.push_back(m);
      }
      j = {{"methods", list}, {"baseline", atmosphere::probe_method_name(results[0].method)}};
    }
    j["geometry"] = geometry;
    j["units"] = "radiance in 1/sr (cd/m^2 per lux of sun)";
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf(
      "probe: altitude %g km, view zenith %g deg azimuth %g deg, sun zenith %g deg azimuth %g deg, %s\n",
      o.altitude_km, o.view_zenith, o.view_azimuth, o.sun_zenith, o.sun_azimuth,
      single ? "single scattering (orders 1)" : "all orders");
  std::printf("%-26s %12s %12s %12s\n", "", "R", "G", "B");
  auto row = [](const std::string& what, const glm::dvec3& v, const std::string& extra) {
    std::printf("%-26s %12.6g %12.6g %12.6g  %s\n", what.c_str(), v.x, v.y, v.z, extra.c_str());
  };
  for (const Evaluated& e : results) {
    const std::string name = atmosphere::probe_method_name(e.method);
    std::string t_extra, l_extra = cost_text(e);
    if (all && &e != &results[0]) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "max rel. error %.3g",
                    max_rel(e.value.transmittance, results[0].value.transmittance));
      t_extra = buf;
      std::snprintf(buf, sizeof buf, "max rel. error %.3g; ",
                    max_rel(e.value.radiance, results[0].value.radiance));
      l_extra = buf + l_extra;
    }
    row(name + "  transmittance", e.value.transmittance, t_extra);
    row(name + "  radiance", e.value.radiance, l_extra);
    if (e.method == ProbeMethod::pathtrace) row("  95% half-width", e.value.radiance_ci95, "");
  }
  std::printf(
      "radiance in 1/sr (cd/m^2 per lux of sun)%s\n",
      all ? (std::string("; errors against ") + atmosphere::probe_method_name(results[0].method)).c_str()
          : "");
  return kOk;
}

}  // namespace

void add_probe_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "probe", "One view ray: transmittance and radiance by any method (GPU LUTs, raymarch, CPU references)");
  cmd->add_option("--scene", o->scene, "Take atmosphere.Atmosphere from this scene file")
      ->check(CLI::ExistingFile);
  cmd->add_option("--preset", o->preset,
                  "Take the atmosphere from a preset of the atmosphere module (earth, mars, ...)");
  cmd->add_option("--set", o->sets,
                  "Override an atmosphere field: atmosphere.mie_g=0.76 or atmosphere.Atmosphere/mie_g=0.76 "
                  "(repeatable)")
      ->allow_extra_args(false)
      ->take_all();
  cmd->add_option("--altitude-km", o->altitude_km, "Camera altitude above the ground")
      ->check(CLI::Range(-1e6, 1e7))
      ->capture_default_str();
  cmd->add_option("--view-zenith-deg,--view-zenith", o->view_zenith, "View zenith angle, degrees")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--view-azimuth-deg,--view-azimuth", o->view_azimuth,
                  "View azimuth, degrees from x towards y (the sun's frame)")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  cmd->add_option("--sun-zenith-deg,--sun-zenith", o->sun_zenith, "Sun zenith angle, degrees")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--sun-azimuth-deg,--sun-azimuth", o->sun_azimuth, "Sun azimuth, degrees from x towards y")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  cmd->add_option("--method", o->method,
                  "reference (CPU quadrature, single scattering), pathtrace (CPU Monte Carlo), lut (Hillaire "
                  "2020 on the GPU), raymarch (per-pixel nested raymarch on the GPU) or all (side by side)")
      ->capture_default_str();
  cmd->add_option("--orders", o->orders,
                  "1: single scattering (GPU methods without the multiple-scattering LUT); all: every order "
                  "(default, except 1 for reference)");
  cmd->add_option("--samples", o->samples, "Paths for pathtrace")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed for pathtrace (same seed and samples: the same result)")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Threads for pathtrace")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd->add_option("--size", o->size, "Frame size WxH at which GPU methods' cost (ms) is measured")
      ->capture_default_str();
  cmd->add_flag(
      "--json", o->json,
      "Machine-readable output: {\"transmittance\":[r,g,b],\"radiance\":[r,g,b],\"method\":...,\"ms\":...}");
  cmd->callback([o, &exit_code] { exit_code = run_probe(*o); });
}

}  // namespace welkin::cli
