// welkin accuracy atmosphere [--out DIR] [--cache FILE] [--size WxH] [--frames N] [--methods lut,raymarch]
//                            [--qualities low,medium,high,ultra] [--threads N] [--quick] [--json]
// The user's "error against run time" report: every method and quality preset evaluated on a fixed set
// of view rays (validation/accuracy_set.h) against the path-traced reference (all orders) and the
// quadrature (single scattering), next to the GPU time of a frame at a stated size. Writes a summary CSV,
// a per-ray CSV and a log-log plot (PNG). Path-traced references are cached in a file (seeded, with
// their sample count and confidence intervals), so reruns cost only the GPU work.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "comparison_panels.h"
#include "error_plot.h"
#include "session.h"
#include "validation/accuracy_set.h"
#include "validation/probe.h"
#include "validation/reference_model.h"
#include "welkin/atmosphere/components.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"


namespace welkin::cli {

void add_accuracy_command(CLI::App& app, int& exit_code);

namespace {

namespace fs = std::filesystem;
namespace ref = welkin::atmosphere::reference;
using atmosphere::Quality;
using atmosphere::SkyMethod;

struct AccuracyOptions {
  std::string technique, out = "out/accuracy", cache, size;  // size: each technique's own default when empty
  std::string ghosting_scene = "assets/scenes/clouds-peer.json";
  std::string scene;  // godrays, clusters, clouds: the scene measured (each has its own default)
  std::string rays, image;  // clouds: a file of view rays; a scene whose path-traced image is made
  int paths_per_pixel = 64;
  bool fit = false, light_only = false, silhouettes = false;
  std::vector<std::string> fit_also, fit_kept_back;
  std::vector<int> fit_terms;
  std::vector<std::string> methods{"lut", "raymarch"}, qualities{"low", "medium", "high", "ultra"};
  int frames = 7, threads = 2;
  bool quick = false, json = false, check = false;
  std::string tolerances;  // --check's table; default: the atmosphere module's validation/accuracy-tolerances.json
  std::string write_tolerances;  // writes this run's measurements as limits (see write_tolerance_table)
  std::vector<double> panorama_suns;  // sun elevations of the sky panoramas against the path tracer
  std::string panorama_size = "24x8";
  uint64_t panorama_paths = 1u << 22;
};

// Rays are grouped by the sun's elevation: where the LUT method's approximations differ most.
enum class Band { day, horizon, dusk, twilight, nautical };
constexpr Band kBands[] = {Band::day, Band::horizon, Band::dusk, Band::twilight, Band::nautical};
Band band_of(const ref::ProbeGeometry& g) {
  const double sun_elevation = 90.0 - g.sun_zenith_deg;
  return sun_elevation >= 3.0    ? Band::day
         : sun_elevation >= 0.0  ? Band::horizon
         : sun_elevation >= -4.5 ? Band::dusk
         : sun_elevation >= -9.0 ? Band::twilight
                                 : Band::nautical;
}
// Each band's name in tables and tolerance files, and in the CSV's column names.
struct BandNames {
  const char* name;
  const char* column;
};
BandNames band_names(Band b) {
  switch (b) {
    case Band::day:
      return {"sun>=3", "sun_ge_3"};
    case Band::horizon:
      return {"sun=0", "sun_0"};
    case Band::dusk:
      return {"sun=-3", "sun_m3"};
    case Band::twilight:
      return {"sun=-6", "sun_m6"};
    case Band::nautical:
      return {"sun=-12", "sun_m12"};
  }
  return {"?", "?"};
}
const char* band_name(Band b) { return band_names(b).name; }

// Below this radiance (1/sr for sun illuminance 1; a clear day's sky is 0.01 to 0.1) a channel is
// black for every purpose, and a relative error there measures nothing.
constexpr double kBlack = 1e-7;

// Relative errors per channel, gathered for a root mean square and a maximum.
struct ErrorStats {
  double sum_sq = 0, max = 0;
  int n = 0;
  void add(const glm::dvec3& value, const glm::dvec3& reference) {
    for (int c = 0; c < 3; ++c) {
      if (!(reference[c] > kBlack)) continue;
      const double e = (value[c] - reference[c]) / reference[c];
      sum_sq += e * e;
      max = std::max(max, std::abs(e));
      ++n;
    }
  }
  void add(const ErrorStats& o) {
    sum_sq += o.sum_sq;
    max = std::max(max, o.max);
    n += o.n;
  }
  double rmse() const { return n ? std::sqrt(sum_sq / n) : 0.0; }
};

struct Config {
  SkyMethod method;
  Quality quality;
  std::string name() const;
};

const char* quality_name(Quality q) {
  switch (q) {
    case Quality::low:
      return "low";
    case Quality::medium:
      return "medium";
    case Quality::high:
      return "high";
    case Quality::ultra:
      return "ultra";
    case Quality::custom:
      return "custom";
  }
  return "?";
}
const char* method_name(SkyMethod m) {
  return m == SkyMethod::raymarch ? "raymarch" : "lut";
}
std::string Config::name() const {
  return std::string(method_name(method)) + "/" + quality_name(quality);
}

struct ConfigResult {
  Config config;
  std::string steps;  // what the preset means for this method
  std::map<Band, ErrorStats> all_orders, single;
  ErrorStats all_orders_plotted;  // sun >= 0: what the plot shows
  atmosphere::FrameCost cost;
};

// The log-log plot of error against GPU time: one series per method.
void write_plot(const std::string& path, const std::vector<ConfigResult>& results, const std::string& size,
                const std::string& renderer) {
  std::vector<PlotSeries> series;
  for (SkyMethod m : {SkyMethod::lut, SkyMethod::raymarch}) {
    PlotSeries s{.name = method_name(m), .colour = m == SkyMethod::lut ? glm::u8vec3(31, 119, 180) : glm::u8vec3(214, 39, 40)};
    for (const ConfigResult& r : results)
      if (r.config.method == m)
        s.points.push_back({r.cost.atmosphere_ms, r.all_orders_plotted.rmse(), r.all_orders_plotted.max,
                            quality_name(r.config.quality)});
    if (!s.points.empty()) series.push_back(std::move(s));
  }
  write_error_plot(path, "welkin accuracy atmosphere: error against GPU time per frame",
                   "path-traced reference, all orders, sun >= 0 deg; " + size + ", " + renderer,
                   "GPU ms per frame, atmosphere passes (log)", series);
}

// ---- The sweep ---------------------------------------------------------------------------------

std::string fmt(double v, const char* f = "%.4g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string steps_of(const atmosphere::Atmosphere& a) {
  const atmosphere::ResolvedQuality q = atmosphere::resolve_quality(a);
  char buf[200];
  if (a.method == SkyMethod::raymarch)
    std::snprintf(buf, sizeof buf, "%d x %d steps per pixel", q.raymarch_steps, q.raymarch_light_steps);
  else
    std::snprintf(buf, sizeof buf, "sky-view %dx%d/%d, transmittance %dx%d/%d, multi-scattering %d/%d",
                  q.sky_view_width, q.sky_view_height, q.sky_view_steps, q.transmittance_width,
                  q.transmittance_height, q.transmittance_steps, q.multiscattering_size,
                  q.multiscattering_steps);
  return buf;
}

// One committed limit (validation/accuracy-tolerances.json): the relative RMSE and worst error a method
// and quality may reach, for all scattering orders against the path tracer or single scattering
// against the quadrature, in one band of sun elevations, over the whole ray set or the quick tenth.
struct Tolerance {
  std::string method, quality, orders, band, rays;
  double rmse = 0.0, max = 0.0;
};

std::vector<Tolerance> read_tolerances(const std::string& file) {
  const nlohmann::json doc = read_json_file(file);
  auto fail = [&](const std::string& path, const std::string& expected, const nlohmann::json& found) {
    return Error(ErrorInfo{.file = file, .path = path, .expected = expected, .found = found.dump()});
  };
  if (!doc.is_object() || !doc.contains("welkin_accuracy_tolerances") || doc["welkin_accuracy_tolerances"] != 1)
    throw fail("/welkin_accuracy_tolerances", "1", doc.is_object() && doc.contains("welkin_accuracy_tolerances") ? doc["welkin_accuracy_tolerances"] : nlohmann::json());
  if (!doc.contains("limits") || !doc["limits"].is_array()) throw fail("/limits", "an array of limits", doc.value("limits", nlohmann::json()));
  const std::vector<std::pair<std::string, std::vector<std::string>>> names{
      {"method", {"lut", "raymarch"}}, {"quality", {"low", "medium", "high", "ultra"}}, {"orders", {"all", "1"}},
      {"band", {"sun>=3", "sun=0", "sun=-3", "sun=-6", "sun=-12"}}, {"rays", {"quick", "all"}}};
  std::vector<Tolerance> out;
  for (size_t i = 0; i < doc["limits"].size(); ++i) {
    const nlohmann::json& e = doc["limits"][i];
    const std::string at = "/limits/" + std::to_string(i);
    if (!e.is_object()) throw fail(at, "an object", e);
    Tolerance t;
    for (const auto& [field, allowed] : names) {
      const nlohmann::json v = e.value(field, nlohmann::json());
      if (!v.is_string() || std::find(allowed.begin(), allowed.end(), v.get<std::string>()) == allowed.end()) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw fail(at + "/" + field, "one of " + list, v);
      }
    }
    t.method = e["method"], t.quality = e["quality"], t.orders = e["orders"], t.band = e["band"], t.rays = e["rays"];
    for (const char* field : {"rmse", "max"}) {
      const nlohmann::json v = e.value(field, nlohmann::json());
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0)
        throw fail(at + "/" + field, "a relative error >= 0", v);
    }
    t.rmse = e["rmse"], t.max = e["max"];
    out.push_back(t);
  }
  return out;
}

// Every limit of the run's ray set that names a measured configuration, against the measurement;
// prints each one exceeded and returns their count (and how many were checked).
std::pair<int, int> check_tolerances(const std::vector<Tolerance>& limits, const std::vector<ConfigResult>& results,
                                     bool quick) {
  int exceeded = 0, checked = 0;
  std::map<std::string, Band> bands;
  for (Band b : kBands) bands[band_name(b)] = b;
  for (const Tolerance& t : limits) {
    if (t.rays != (quick ? "quick" : "all")) continue;
    for (const ConfigResult& r : results) {
      if (t.method != method_name(r.config.method) || t.quality != quality_name(r.config.quality)) continue;
      const auto& set = t.orders == "all" ? r.all_orders : r.single;
      const auto it = set.find(bands.at(t.band));
      if (it == set.end() || it->second.n == 0) continue;
      ++checked;
      const double rmse = it->second.rmse(), max = it->second.max;
      if (rmse > t.rmse || max > t.max) {
        ++exceeded;
        std::fprintf(stderr, "accuracy check: %s %s, orders %s, %s: RMSE %.2f%% (limit %.2f%%), worst %.2f%% (limit %.2f%%)\n",
                     t.method.c_str(), t.quality.c_str(), t.orders.c_str(), t.band.c_str(), 100 * rmse, 100 * t.rmse,
                     100 * max, 100 * t.max);
      }
    }
  }
  return {exceeded, checked};
}

// Writes the run's measurements as the limits of its ray set (quick or all), each the measured value
// plus 15% and 0.1 percentage point, keeping the other set's limits from `keep` (the table in use).
void write_tolerance_table(const std::string& path, const std::vector<Tolerance>& keep,
                           const std::vector<ConfigResult>& results, bool quick) {
  const std::string rays = quick ? "quick" : "all";
  nlohmann::json limits = nlohmann::json::array();
  auto add = [&](const Tolerance& t) {
    limits.push_back({{"method", t.method}, {"quality", t.quality}, {"orders", t.orders}, {"band", t.band},
                      {"rays", t.rays}, {"rmse", t.rmse}, {"max", t.max}});
  };
  auto limit = [](double measured) { return std::ceil((measured * 1.15 + 0.001) * 1e4) / 1e4; };
  for (const Tolerance& t : keep)
    if (t.rays != rays) add(t);
  for (const ConfigResult& r : results)
    for (const char* orders : {"all", "1"}) {
      const auto& set = std::string(orders) == "all" ? r.all_orders : r.single;
      for (Band b : kBands) {
        const auto it = set.find(b);
        if (it == set.end() || it->second.n == 0) continue;
        add({.method = method_name(r.config.method), .quality = quality_name(r.config.quality), .orders = orders,
             .band = band_name(b), .rays = rays, .rmse = limit(it->second.rmse()), .max = limit(it->second.max)});
      }
    }
  const nlohmann::json doc{
      {"welkin_accuracy_tolerances", 1},
      {"note",
       "Limits of `welkin accuracy atmosphere --check`: relative RMSE and worst relative error of radiance per "
       "method, quality, scattering orders (all: against the path-traced references; 1: single scattering "
       "against the quadrature), band of sun elevation and ray set (quick: every tenth ray, what CI runs; all: "
       "the rays of the README's table). Each is the measured value at the time of writing plus 15% and 0.1 "
       "percentage point (written by `welkin accuracy atmosphere --write-tolerances`): a regression guard."},
      {"limits", limits}};
  write_file_atomically(path, doc.dump(1) + "\n");
}

// The whole sky from the ground, LUT path at `high` against the path tracer, for looking at: one
// image per sun elevation, the LUT's panorama above the path tracer's and their relative difference
// below (red: the LUT too bright, blue: too dark; full at 20%). Azimuth runs across from -180 to 180
// degrees from the sun's (the sun's in the middle), elevation up from the horizon, rows crowded
// towards it. Both panoramas share one exposure, the path tracer's 97th percentile, and a 1/2.2 curve.
void write_panoramas(const AccuracyOptions& o, const ref::AtmosphereModel& model, const std::string& renderer) {
  int w = 0, h = 0;
  parse_size(o.panorama_size, w, h);
  if (w > 360 || h > 90)
    throw Error(ErrorInfo{.path = "--panorama-size", .expected = "at most 360x90 rays", .found = o.panorama_size});
  constexpr int kCell = 8;
  const atmosphere::Atmosphere earth;
  atmosphere::GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/false);
  const atmosphere::ReferenceSettings settings{.samples = o.panorama_paths,
                                              .samples_sun_below_horizon = o.panorama_paths,
                                              .samples_deep_twilight = o.panorama_paths};
  auto luminance = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  for (double sun : o.panorama_suns) {
    if (!(sun >= -18.0 && sun <= 90.0))
      throw Error(ErrorInfo{.path = "--panorama", .expected = "sun elevations from -18 to 90 degrees", .found = fmt(sun)});
    std::vector<glm::dvec3> lut(size_t(w) * h), pt(size_t(w) * h), ci(size_t(w) * h);
    ErrorStats errors;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const double t = (h - 1 - y + 0.5) / h;  // the top row is the highest
        const ref::ProbeGeometry g{.altitude_km = 0.0,
                                   .view_zenith_deg = 90.0 - 90.0 * t * t,
                                   .view_azimuth_deg = -180.0 + 360.0 * (x + 0.5) / w,
                                   .sun_zenith_deg = 90.0 - sun,
                                   .sun_azimuth_deg = 0.0};
        const size_t i = size_t(y) * w + x;
        lut[i] = probe.evaluate(g).radiance;
        const atmosphere::CachedReference r = atmosphere::path_trace_reference(model, g, settings, o.threads);
        pt[i] = r.radiance, ci[i] = r.ci95;
        errors.add(lut[i], pt[i]);
      }
      std::fprintf(stderr, "\rpanorama, sun %g: row %d/%d", sun, y + 1, h);
    }
    ComparisonPanels panels{.width = w, .height = h, .approximation = lut, .reference = pt};
    double ci_sum = 0.0;
    for (size_t i = 0; i < pt.size(); ++i) {
      const double ref_l = luminance(pt[i]);
      panels.relative.push_back(ref_l > 0.0 ? (luminance(lut[i]) - ref_l) / ref_l : 0.0);
      ci_sum += ref_l > 0.0 ? luminance(ci[i]) / ref_l : 0.0;
    }
    char name[64];
    std::snprintf(name, sizeof name, "panorama-sun%+g.png", sun);
    const std::string path = (fs::path(o.out) / name).string();
    write_comparison_panels(path, panels, kCell, 0.2);
    std::fprintf(stderr, "\n");
    std::printf("panorama, sun %g deg (%dx%d rays from the ground, %llu paths each, %s): LUT at high against the "
                "path tracer, RMSE %.1f%%, worst %.1f%% over rays and channels; mean 95%% half-width of the "
                "references %.1f%%; wrote %s\n",
                sun, w, h, (unsigned long long)o.panorama_paths, renderer.c_str(), 100 * errors.rmse(),
                100 * errors.max, 100 * ci_sum / (w * h), path.c_str());
  }
}

int run_accuracy(const AccuracyOptions& options) {
  AccuracyOptions o = options;
  if ((o.check || !o.tolerances.empty()) && o.technique != "atmosphere")
    throw Error(ErrorInfo{.path = "--check", .expected = "the atmosphere technique (the only one with a tolerance table)",
                          .found = "'" + o.technique + "'"});
  if (o.technique == "godrays")
    return run_god_ray_accuracy({.out = o.out, .size = o.size.empty() ? "320x180" : o.size,
                                 .scene = o.scene.empty() ? GodRayAccuracyOptions{}.scene : o.scene,
                                 .frames = o.frames, .quick = o.quick, .json = o.json});
  if (o.technique == "clusters")
    return run_cluster_accuracy({.out = o.out, .size = o.size.empty() ? "320x180" : o.size,
                                 .scene = o.scene.empty() ? ClusterAccuracyOptions{}.scene : o.scene, .frames = o.frames,
                                 .quick = o.quick, .json = o.json});
  if (o.technique == "billboards")
    return run_billboard_accuracy({.out = o.out, .size = o.size.empty() ? "320x180" : o.size,
                                   .scene = o.scene.empty() ? BillboardAccuracyOptions{}.scene : o.scene,
                                   .frames = o.frames, .quick = o.quick, .json = o.json});
  if (o.technique == "clouds")
    return run_cloud_accuracy({.out = o.out, .size = o.size.empty() ? (o.image.empty() ? "640x360" : "96x54") : o.size,
                               .ghosting_scene = o.ghosting_scene, .scene = o.scene, .rays = o.rays, .image = o.image,
                               .cache = o.cache, .paths_per_pixel = o.paths_per_pixel, .fit = o.fit, .fit_also = o.fit_also,
                               .fit_kept_back = o.fit_kept_back, .fit_terms = o.fit_terms, .light_only = o.light_only,
                               .silhouettes_only = o.silhouettes,
                               .qualities = o.qualities, .frames = o.frames,
                               .quick = o.quick, .json = o.json});
  if (o.size.empty()) o.size = "640x360";
  if (o.technique != "atmosphere")
    throw Error(ErrorInfo{.path = "technique", .expected = "atmosphere, clouds, clusters, billboards or godrays", .found = "'" + o.technique + "'"});
  int width = 0, height = 0;
  parse_size(o.size, width, height);
  std::vector<Config> configs;
  for (const std::string& m : o.methods) {
    if (m != "lut" && m != "raymarch")
      throw Error(ErrorInfo{.path = "--methods", .expected = "lut or raymarch", .found = "'" + m + "'"});
    for (const std::string& q : o.qualities) {
      const std::map<std::string, Quality> names{{"low", Quality::low},
                                                 {"medium", Quality::medium},
                                                 {"high", Quality::high},
                                                 {"ultra", Quality::ultra}};
      if (!names.count(q))
        throw Error(ErrorInfo{
            .path = "--qualities", .expected = "low, medium, high or ultra", .found = "'" + q + "'"});
      configs.push_back({m == "raymarch" ? SkyMethod::raymarch : SkyMethod::lut, names.at(q)});
    }
  }
  fs::create_directories(o.out);

  // The default atmosphere (Earth), exactly as the module gives it to the GPU.
  auto world = make_world();
  world->modules().require_component("atmosphere.Atmosphere");
  const fs::path validation = world->modules().manifest("atmosphere")->data_dir / "validation";
  std::vector<Tolerance> limits;
  const std::string table = o.tolerances.empty() ? (validation / "accuracy-tolerances.json").string() : o.tolerances;
  if (o.check || !o.write_tolerances.empty()) limits = read_tolerances(table);
  const atmosphere::Atmosphere earth;
  const ref::AtmosphereModel model = atmosphere::to_reference(earth);
  if (!o.panorama_suns.empty()) {
    auto context = create_headless_context();
    write_panoramas(o, model, context->info().renderer);
    return kOk;
  }
  std::vector<ref::ProbeGeometry> rays = atmosphere::accuracy_rays();
  if (o.quick) {
    // A spread-out tenth of the set: a smoke test of the whole pipeline.
    std::vector<ref::ProbeGeometry> some;
    for (size_t i = 0; i < rays.size(); i += 10) some.push_back(rays[i]);
    rays = some;
  }

  // Path-traced references: the cache beside the module's sources when there is one.
  std::string cache_path = o.cache;
  if (cache_path.empty()) {
    const fs::path beside = validation / "accuracy-references.json";
    cache_path =
        fs::exists(beside) ? beside.string() : (fs::path(o.out) / "accuracy-references.json").string();
  }
  atmosphere::ReferenceCache cache(model, atmosphere::ReferenceSettings{});
  const size_t cached = cache.load(cache_path);
  size_t missing = 0;
  for (const auto& g : rays) missing += cache.find(g) ? 0 : 1;
  std::fprintf(stderr, "references: %zu cached in %s, %zu to path trace (%llu paths each, %llu with the sun below the horizon)\n", cached,
               cache_path.c_str(), missing, (unsigned long long)cache.settings().samples,
               (unsigned long long)cache.settings().samples_sun_below_horizon);
  size_t done = 0;
  for (const auto& g : rays) {
    if (cache.find(g)) continue;
    cache.put(g, atmosphere::path_trace_reference(model, g, cache.settings(), o.threads));
    std::fprintf(stderr, "\rpath tracing %zu/%zu", ++done, missing);
    if (done % 16 == 0 || done == missing) cache.save(cache_path);
  }
  if (missing) std::fprintf(stderr, "\n");
  std::vector<atmosphere::ProbeValue> quadrature;
  for (const auto& g : rays) quadrature.push_back(atmosphere::probe_reference(model, g));

  auto context = create_headless_context();
  const std::string renderer = context->info().renderer;
  const ref::ProbeGeometry cost_view{.altitude_km = 0.0, .view_zenith_deg = 80.0, .sun_zenith_deg = 60.0};
  std::vector<ConfigResult> results;
  std::ostringstream rays_csv;  // written atomically once complete
  rays_csv
      << "method,quality,orders,altitude_km,sun_elevation_deg,view_elevation_deg,view_azimuth_from_sun_deg,"
         "reference_r,reference_g,reference_b,reference_ci95_r,reference_ci95_g,reference_ci95_b,value_r,"
         "value_g,value_b,rel_error_r,rel_error_g,rel_error_b\n";
  for (const Config& cfg : configs) {
    atmosphere::Atmosphere a = earth;
    a.method = cfg.method;
    a.quality = cfg.quality;
    ConfigResult r{.config = cfg, .steps = steps_of(a)};
    for (bool single : {false, true}) {
      atmosphere::GpuProbe probe(a, cfg.method, single);
      for (size_t i = 0; i < rays.size(); ++i) {
        const ref::ProbeGeometry& g = rays[i];
        const atmosphere::ProbeValue v = probe.evaluate(g);
        glm::dvec3 reference, ci;
        if (single) {
          reference = quadrature[i].radiance, ci = quadrature[i].radiance_ci95;
          r.single[band_of(g)].add(v.radiance, reference);
        } else {
          const atmosphere::CachedReference c = *cache.find(g);
          reference = c.radiance, ci = c.ci95;
          r.all_orders[band_of(g)].add(v.radiance, reference);
          if (g.sun_zenith_deg <= 90.0) r.all_orders_plotted.add(v.radiance, reference);
        }
        rays_csv << method_name(cfg.method) << "," << quality_name(cfg.quality) << ","
                 << (single ? "1" : "all") << "," << g.altitude_km << "," << 90.0 - g.sun_zenith_deg << ","
                 << 90.0 - g.view_zenith_deg << "," << g.view_azimuth_deg;
        for (int c = 0; c < 3; ++c) rays_csv << "," << fmt(reference[c], "%.6g");
        for (int c = 0; c < 3; ++c) rays_csv << "," << fmt(ci[c], "%.3g");
        for (int c = 0; c < 3; ++c) rays_csv << "," << fmt(v.radiance[c], "%.6g");
        for (int c = 0; c < 3; ++c)
          rays_csv << ","
                   << fmt(reference[c] > 0 ? (v.radiance[c] - reference[c]) / reference[c] : 0.0, "%.4g");
        rays_csv << "\n";
      }
      if (!single) r.cost = probe.frame_cost(cost_view, width, height, o.frames);
      std::fprintf(stderr, "\r%-16s orders %-3s done", cfg.name().c_str(), single ? "1" : "all");
    }
    results.push_back(r);
  }
  std::fprintf(stderr, "\n");

  write_file_atomically((fs::path(o.out) / "accuracy-atmosphere-rays.csv").string(), rays_csv.str());
  if (!o.write_tolerances.empty()) write_tolerance_table(o.write_tolerances, limits, results, o.quick);
  int status = kOk;
  if (o.check) {
    const auto [exceeded, checked] = check_tolerances(limits, results, o.quick);
    std::fprintf(stderr, "accuracy check: %d of %d limits exceeded (%s rays)\n", exceeded, checked, o.quick ? "quick" : "all");
    if (checked == 0) {
      std::fprintf(stderr, "accuracy check: no limit names what was measured\n");
      status = kFailure;
    }
    if (exceeded > 0) status = kFailure;
  }
  std::ostringstream csv;
  csv << "method,quality,steps,frame_size,atmosphere_ms,sky_pass_ms,frame_ms,copy_ms,all_orders_rel_rmse_sun_ge_0,"
         "all_orders_max_sun_ge_0";
  for (const char* orders : {"all_orders", "single"})
    for (Band b : kBands) {
      const char* column = band_names(b).column;
      csv << "," << orders << "_rel_rmse_" << column << "," << orders << "_max_" << column;
    }
  csv << "\n";
  for (ConfigResult& r : results) {
    csv << method_name(r.config.method) << "," << quality_name(r.config.quality) << ",\"" << r.steps << "\","
        << width << "x" << height << "," << fmt(r.cost.atmosphere_ms) << "," << fmt(r.cost.sky_ms) << ","
        << fmt(r.cost.frame_ms) << "," << fmt(r.cost.copy_ms) << "," << fmt(r.all_orders_plotted.rmse())
        << "," << fmt(r.all_orders_plotted.max);
    for (Band b : kBands) csv << "," << fmt(r.all_orders[b].rmse()) << "," << fmt(r.all_orders[b].max);
    for (Band b : kBands) csv << "," << fmt(r.single[b].rmse()) << "," << fmt(r.single[b].max);
    csv << "\n";
  }
  write_file_atomically((fs::path(o.out) / "accuracy-atmosphere.csv").string(), csv.str());
  const std::string png = (fs::path(o.out) / "accuracy-atmosphere.png").string();
  write_plot(png, results, std::to_string(width) + "x" + std::to_string(height), renderer);

  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (ConfigResult& r : results) {
      nlohmann::json bands_all, bands_single;
      for (Band b : kBands) {
        bands_all[band_name(b)] = {{"rel_rmse", r.all_orders[b].rmse()}, {"max", r.all_orders[b].max}};
        bands_single[band_name(b)] = {{"rel_rmse", r.single[b].rmse()}, {"max", r.single[b].max}};
      }
      list.push_back({{"method", method_name(r.config.method)},
                      {"quality", quality_name(r.config.quality)},
                      {"steps", r.steps},
                      {"atmosphere_ms", r.cost.atmosphere_ms},
                      {"sky_pass_ms", r.cost.sky_ms},
                      {"frame_ms", r.cost.frame_ms},
                      {"copy_ms", r.cost.copy_ms},
                      {"all_orders_vs_pathtrace", bands_all},
                      {"single_vs_quadrature", bands_single}});
    }
    std::printf("%s\n", nlohmann::json{{"rays", rays.size()},
                                       {"frame_size", std::to_string(width) + "x" + std::to_string(height)},
                                       {"renderer", renderer},
                                       {"reference_samples", cache.settings().samples},
                                       {"reference_samples_sun_below_horizon",
                                        cache.settings().samples_sun_below_horizon},
                                       {"reference_seed", cache.settings().seed},
                                       {"results", list},
                                       {"csv", (fs::path(o.out) / "accuracy-atmosphere.csv").string()},
                                       {"plot", png}}
                            .dump(2)
                            .c_str());
    return status;
  }
  std::printf("%zu rays; reference: path tracing, %llu paths per ray, %llu with the sun below the horizon "
              "(seed %llu), cached in %s\n",
              rays.size(), (unsigned long long)cache.settings().samples,
              (unsigned long long)cache.settings().samples_sun_below_horizon,
              (unsigned long long)cache.settings().seed, cache_path.c_str());
  std::printf("GPU time: median of %d frames at %dx%d on %s, forced to completion; copy = full-screen copy\n",
              o.frames, width, height, renderer.c_str());
  std::printf(
      "relative error of radiance: RMSE / max over rays and channels (channels darker than %g 1/sr "
      "left out)\n\n",
      kBlack);
  std::printf(
      "| method | quality | atmosphere ms | sky pass ms | copy ms | all orders sun>=0 | sun>=3 | sun=0 | sun=-3 | "
      "sun=-6 | sun=-12 | single sun>=3 | single sun=0 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  auto pair = [](const ErrorStats& s) {
    return fmt(s.rmse() * 100, "%.1f") + "% / " + fmt(s.max * 100, "%.1f") + "%";
  };
  for (ConfigResult& r : results)
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", method_name(r.config.method),
                quality_name(r.config.quality), fmt(r.cost.atmosphere_ms, "%.2f").c_str(),
                fmt(r.cost.sky_ms, "%.2f").c_str(), fmt(r.cost.copy_ms, "%.2f").c_str(),
                pair(r.all_orders_plotted).c_str(), pair(r.all_orders[Band::day]).c_str(),
                pair(r.all_orders[Band::horizon]).c_str(), pair(r.all_orders[Band::dusk]).c_str(),
                pair(r.all_orders[Band::twilight]).c_str(), pair(r.all_orders[Band::nautical]).c_str(),
                pair(r.single[Band::day]).c_str(), pair(r.single[Band::horizon]).c_str());
  std::printf("\nwrote %s, %s and %s\n", (fs::path(o.out) / "accuracy-atmosphere.csv").string().c_str(),
              (fs::path(o.out) / "accuracy-atmosphere-rays.csv").string().c_str(), png.c_str());
  return status;
}

}  // namespace

void add_accuracy_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AccuracyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "accuracy", "Error against run time of every method and quality preset of a technique (CSV and plot)");
  cmd->add_option("technique", o->technique, "The technique to measure: atmosphere, clouds, clusters, billboards, godrays")->required();
  cmd->add_option("--out", o->out, "Folder for the CSVs and the plot")->capture_default_str();
  cmd->add_option(
      "--cache", o->cache,
      "Path-traced reference cache (atmosphere: default the module's validation/ folder, else --out; clouds: the "
      "rays path traced, default $WELKIN_CACHE_DIR, $XDG_CACHE_HOME/welkin or ~/.cache/welkin)");
  cmd->add_option("-s,--size", o->size, "Frame size WxH for GPU time (godrays: also of the measured frame; default 320x180, else 640x360)");
  cmd->add_option("--ghosting-scene", o->ghosting_scene, "clouds: the scene the temporal upscaling flies through")
      ->capture_default_str();
  cmd->add_option("--scene", o->scene,
                  "godrays, clusters: the scene whose frame is measured (default assets/scenes/godrays-sunset.json, "
                  "clouds-clusters.json); clouds: the scene whose layers and sun are measured (default: a cumulus "
                  "layer under a sun 40 degrees up)");
  cmd->add_option("--rays", o->rays,
                  "clouds: the view rays measured, JSON {\"rays\": [{\"position_m\": [east, north, up], "
                  "\"heading_deg\": h, \"pitch_deg\": p}, ...]} (default: 18 rays below, inside, above the layer and "
                  "from orbit)");
  cmd->add_option("--image", o->image,
                  "clouds: instead of the sweep, the scene's view marched at each quality beside the path tracer's "
                  "image of the same rays and their difference (size from --size, default 96x54)");
  cmd->add_flag("--fit", o->fit,
               "clouds: fit the light model's weights to the path tracer on the rays measured (at the --qualities "
               "given) and write light_model_fit.glsl into --out");
  cmd->add_option("--fit-also", o->fit_also,
                  "clouds --fit: a further training set, SCENE,RAYS (two files; repeat for more)");
  cmd->add_option("--fit-kept-back", o->fit_kept_back,
                  "clouds --fit: a set marched term by term and reported after the fit but not fitted, SCENE,RAYS "
                  "(repeat for more)");
  cmd->add_option("--fit-terms", o->fit_terms,
                  "clouds --fit: the candidate terms solved for, by number (light_model.glsl; default: all)")
      ->delimiter(',');
  cmd->add_flag("--light-only", o->light_only,
                "clouds: the rays' errors and the light model's term budget only (no GPU time, ghosting or aerial perspective)");
  cmd->add_flag("--silhouettes", o->silhouettes,
                "clouds: only the temporal upscaling's silhouettes in --ghosting-scene, still, turning 1 degree a frame "
                "and flying (frames at half --size)");
  cmd->add_option("--paths-per-pixel", o->paths_per_pixel,
                  "clouds --image: paths per pixel of the path-traced image (0: none; the shipped frame against the "
                  "march at every pixel)")
      ->check(CLI::Range(0, 65536))
      ->capture_default_str();
  cmd->add_option("-n,--frames", o->frames, "Frames per GPU time (median)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--methods", o->methods, "Methods: lut, raymarch")->delimiter(',')->capture_default_str();
  cmd->add_option("--qualities", o->qualities, "Quality presets: low, medium, high, ultra")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Threads for path tracing missing references")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd->add_flag("--quick", o->quick, "Every tenth ray only (a smoke test)");
  cmd->add_flag("--check", o->check, "atmosphere: exit 1 when an error exceeds its limit in the tolerance table");
  cmd->add_option("--tolerances", o->tolerances, "atmosphere --check: the table (default: the module's validation/accuracy-tolerances.json)");
  cmd->add_option("--panorama", o->panorama_suns,
                  "atmosphere: instead of the sweep, whole-sky panoramas from the ground at these sun elevations "
                  "(degrees), the LUT path at high above the path tracer's, and their difference")
      ->delimiter(',');
  cmd->add_option("--panorama-size", o->panorama_size, "atmosphere --panorama: rays across and up")->capture_default_str();
  cmd->add_option("--panorama-paths", o->panorama_paths, "atmosphere --panorama: paths per ray")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32))
      ->capture_default_str();
  cmd->add_option("--write-tolerances", o->write_tolerances,
                  "atmosphere: write this run's errors (+15% and 0.1 point) as the limits of its ray set, keeping the "
                  "other set's from the table in use");
  cmd->add_flag("--json", o->json, "Machine-readable summary");
  cmd->callback([o, &exit_code] { exit_code = run_accuracy(*o); });
}

}  // namespace welkin::cli
