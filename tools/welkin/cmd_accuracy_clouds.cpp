// welkin accuracy clouds [--out DIR] [--size WxH] [--frames N] [--qualities ...] [--quick] [--json]
//                        [--ghosting-scene SCENE] [--silhouettes]
// The clouds' "error against run time": each quality preset and multiple-scattering model marched
// on view rays from below, inside and above a cumulus layer and from orbit, against the path-traced
// radiance of the same rays through the same field (validation/cloud_probe.h), next to the GPU time of the
// clouds' passes per frame at a stated size. Writes a summary CSV, a per-ray CSV and a log-log plot.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <map>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "error_plot.h"
#include "session.h"
#include "validation/cloud_probe.h"
#include "validation/silhouettes.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"
#include "welkin/atmosphere/components.h"
#include "welkin/gfx/debug_content.h"
#include "comparison_panels.h"
#include "cloud_light_fit.h"
#include "cloud_image.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;
using clouds::CloudView;
using clouds::MultipleScattering;
using clouds::Quality;

struct CloudConfig {
  Quality quality;
  MultipleScattering model;
  std::string name;
};

// Sun 40 degrees up; a cumulus layer 1.5-2.7 km with 60% coverage.
clouds::VolumetricClouds measured_clouds() {
  clouds::VolumetricClouds c;
  c.layers = {clouds::CloudLayer{.genus = clouds::Genus::cumulus, .base_altitude_m = 1500.0f, .thickness_m = 1200.0f,
                                 .coverage = 0.6f, .density_per_m = 0.03f}};
  c.weather_system_amount = 0.0f;  // the layer's own coverage everywhere: the lighting is what is measured
  // Shadows on (the default): the march reads the optical depth beyond its light steps from the shadow map.
  return c;
}

}  // namespace

MeasuredCase case_from_scene(const std::string& file) {
  if (file.empty()) return {measured_clouds()};
  auto world = make_world();
  load_scene_file(*world, file);
  world->update(FrameInfo{});
  Registry& reg = world->registry();
  MeasuredCase m;
  const Entity clouds = reg.first<clouds::VolumetricClouds>();
  if (clouds.is_null())
    throw Error(ErrorInfo{.file = file, .path = "/entities", .expected = "an entity with clouds.VolumetricClouds", .found = "none"});
  m.clouds = *reg.get<clouds::VolumetricClouds>(clouds);
  if (const Entity sun = reg.first<atmosphere::Sun>(); !sun.is_null())
    m.sun_azimuth_deg = reg.get<atmosphere::Sun>(sun)->azimuth_deg, m.sun_elevation_deg = reg.get<atmosphere::Sun>(sun)->elevation_deg;
  else if (const Entity light = reg.first<DirectionalLight>(); !light.is_null())
    m.sun_azimuth_deg = reg.get<DirectionalLight>(light)->azimuth_deg, m.sun_elevation_deg = reg.get<DirectionalLight>(light)->elevation_deg;
  else
    throw Error(ErrorInfo{.file = file, .path = "/entities", .expected = "an entity with atmosphere.Sun or core.DirectionalLight", .found = "none"});
  if (!(m.sun_elevation_deg > 0.0))
    throw Error(ErrorInfo{.file = file, .path = "/entities (the sun)", .expected = "a sun above the horizon (the probe's light is the sun alone)",
                          .found = "elevation " + std::to_string(m.sun_elevation_deg) + " degrees"});
  if (const Entity camera = reg.first<Camera>(); !camera.is_null()) m.camera = *reg.get<Camera>(camera);
  return m;
}

namespace {

// --rays FILE: {"rays": [{"position_m": [east, north, up], "heading_deg": h, "pitch_deg": p}, ...]}, at most
// kMaxRays rays, every value a finite number, pitch within [-90, 90] degrees.
std::vector<CloudView> read_rays(const std::string& file) {
  constexpr size_t kMaxRays = 4096;
  const nlohmann::json doc = read_json_file(file);
  auto fail = [&](const std::string& path, const std::string& expected, const nlohmann::json& found) {
    return Error(ErrorInfo{.file = file, .path = path, .expected = expected, .found = describe_json(found)});
  };
  if (!doc.is_object() || !doc.contains("rays")) throw fail("", "an object with \"rays\": [...]", doc);
  for (const auto& [key, value] : doc.items())
    if (key != "rays") throw fail("/" + key, "only \"rays\"", value);
  const nlohmann::json& rays = doc["rays"];
  if (!rays.is_array() || rays.empty() || rays.size() > kMaxRays)
    throw fail("/rays", "an array of 1 to " + std::to_string(kMaxRays) + " rays", rays);
  auto number = [&](const nlohmann::json& j, const std::string& path, double lo, double hi) {
    if (!j.is_number() || !std::isfinite(j.get<double>()) || j.get<double>() < lo || j.get<double>() > hi)
      throw fail(path, "a number from " + std::to_string(lo) + " to " + std::to_string(hi), j);
    return j.get<double>();
  };
  std::vector<CloudView> views;
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::string at = "/rays/" + std::to_string(i);
    const nlohmann::json& r = rays[i];
    if (!r.is_object()) throw fail(at, "an object", r);
    for (const char* key : {"position_m", "heading_deg", "pitch_deg"})
      if (!r.contains(key)) throw fail(at + "/" + key, "a value", nlohmann::json());
    for (const auto& [key, value] : r.items())
      if (key != "position_m" && key != "heading_deg" && key != "pitch_deg")
        throw fail(at + "/" + key, "position_m, heading_deg or pitch_deg", value);
    const nlohmann::json& p = r["position_m"];
    if (!p.is_array() || p.size() != 3) throw fail(at + "/position_m", "[east, north, up] in metres", p);
    CloudView v{.name = "ray " + std::to_string(i)};
    v.east_m = number(p[0], at + "/position_m/0", -1e7, 1e7);
    v.north_m = number(p[1], at + "/position_m/1", -1e7, 1e7);
    v.altitude_m = number(p[2], at + "/position_m/2", 0.0, 1e8);
    v.heading_deg = number(r["heading_deg"], at + "/heading_deg", -360.0, 360.0);
    v.pitch_deg = number(r["pitch_deg"], at + "/pitch_deg", -90.0, 90.0);
    views.push_back(v);
  }
  return views;
}

std::vector<CloudView> measured_views(bool quick) {
  std::vector<CloudView> v;
  for (double heading : {0.0, 90.0, 180.0, 270.0})
    for (double pitch : {30.0, 60.0, 85.0}) v.push_back({"below", 100.0, heading, pitch});
  for (double heading : {30.0, 150.0, 250.0}) v.push_back({"inside", 2000.0, heading, 10.0});
  for (double heading : {0.0, 120.0, 200.0}) v.push_back({"above", 4000.0, heading, -40.0});
  for (double heading : {20.0, 200.0}) v.push_back({"orbit", 1.0e6, heading, -88.0});
  if (quick) v = {v[0], v[12], v[15], v[18]};
  return v;
}

// Ghosting of the temporal upscaling: a scene (the peer scene by default) with the camera flying and turning, each frame's
// result against the same quality marched at every pixel, with the history clipped and without.
struct Ghosting {
  double clipped_mean = 0.0, clipped_worst = 0.0, plain_mean = 0.0, plain_worst = 0.0;
};

ImageF render_flying(World& world, Renderer& renderer, int frame, int width, int height) {
  Registry& reg = world.registry();
  Camera& cam = *reg.get<Camera>(reg.first<Camera>());
  cam.position_m = {-20.0 * frame, -40.0 * frame, 100.0 + 5.0 * frame};  // 45 m per frame, climbing
  cam.heading_deg = 210.0f + 0.6f * float(frame);
  renderer.render_frame(FrameInfo{.time_s = frame / 30.0, .index = uint64_t(frame)}, width, height);
  return renderer.read_hdr();
}

Ghosting measure_ghosting(const std::string& scene, int frames, int width, int height) {
  auto world_for = [&scene](bool temporal, bool clipping) {
    auto w = make_world();
    load_scene_file(*w, scene);
    auto& c = *w->registry().get<clouds::VolumetricClouds>(w->registry().first<clouds::VolumetricClouds>());
    c.temporal_upscaling = temporal, c.temporal_clipping = clipping;
    return w;
  };
  auto reference_world = world_for(false, true), clipped_world = world_for(true, true), plain_world = world_for(true, false);
  Renderer reference(*reference_world), clipped(*clipped_world), plain(*plain_world);
  Ghosting g;
  int counted = 0;
  for (int f = 0; f < frames; ++f) {
    const ImageF r = render_flying(*reference_world, reference, f, width, height);
    const ImageF a = render_flying(*clipped_world, clipped, f, width, height);
    const ImageF b = render_flying(*plain_world, plain, f, width, height);
    if (f < 4) continue;  // the history fills in the first four frames
    double ea = 0.0, eb = 0.0, total = 0.0;
    for (size_t i = 0; i < r.rgba.size(); ++i)
      if (i % 4 != 3) ea += std::abs(a.rgba[i] - r.rgba[i]), eb += std::abs(b.rgba[i] - r.rgba[i]), total += r.rgba[i];
    g.clipped_mean += ea / total, g.plain_mean += eb / total;
    g.clipped_worst = std::max(g.clipped_worst, ea / total), g.plain_worst = std::max(g.plain_worst, eb / total);
    ++counted;
    std::fprintf(stderr, "\rghosting frame %d/%d", f + 1, frames);
  }
  std::fprintf(stderr, "\n");
  g.clipped_mean /= std::max(counted, 1), g.plain_mean /= std::max(counted, 1);
  return g;
}

// The temporal upscaling's silhouettes (validation/silhouettes.h): the scene still, turning 1 degree a
// frame (`welkin bench --turn-deg 1`) and flying, upscaled against a march of every pixel, at the full
// march's silhouettes (its opacity steps by more than 0.1 between neighbours).
void report_silhouettes(const std::string& scene, int frames, int width, int height) {
  std::printf(
      "\ntemporal upscaling at silhouettes (%s at its quality, %dx%d, %d frames after 4 that fill the\n"
      "history): mean |upscaled - every pixel marched| luminance at the full march's silhouettes, of the\n"
      "frame's mean; the clouds' opacity there; relative L1 over the frame\n",
      scene.c_str(), width, height, frames);
  for (clouds::SilhouetteMotion motion : {clouds::SilhouetteMotion::still, clouds::SilhouetteMotion::turning,
                                          clouds::SilhouetteMotion::flying}) {
    auto upscaled_world = make_world(), full_world = make_world();
    load_scene_file(*upscaled_world, scene), load_scene_file(*full_world, scene);
    for (World* w : {upscaled_world.get(), full_world.get()}) {
      auto& c = *w->registry().get<clouds::VolumetricClouds>(w->registry().first<clouds::VolumetricClouds>());
      c.temporal_upscaling = true;
      w->registry().get<Camera>(w->registry().first<Camera>())->moving_render_scale = 1.0f;
    }
    Renderer upscaled(*upscaled_world), full(*full_world);
    const clouds::SilhouetteError e = clouds::measure_silhouettes(
        {*upscaled_world, upscaled}, {*full_world, full}, motion, 4, frames, width, height);
    std::printf(
        "  %-8s %6.2f%% at %zu silhouette pixels, opacity %.3f; frame %.2f%%; %.0f%% of the march's pixels "
        "near a silhouette\n",
        clouds::motion_name(motion), 100 * e.silhouette, e.pixels, e.opacity, 100 * e.frame,
        100 * e.near_silhouette);
  }
}

// Aerial perspective along the ray against takram's single mean depth, in hazy air, the same march
// (30 m steps, every pixel) with each. Two scenes: sparse clouds from 2 to 60 km, and one built for the
// failure: a translucent sheet 10-20 km away in front of an opaque deck 30-60 km away, so that most
// pixels see two clouds at very different depths and the mean depth lies between them. Writes the two
// frames and the relative difference (x10, red) side by side.
struct ApComparison {
  double mean = 0.0, worst = 0.0;
  int cloud_pixels = 0;
};

struct ApCase {
  const char* name;
  double altitude_m, pitch_deg;
  nlohmann::json layers;
};

const ApCase kSparseClouds{"sparse clouds 2-60 km", 300.0, 3.0,
                           {{{"genus", "cumulus"}, {"base_altitude_m", 1200}, {"thickness_m", 1000}, {"coverage", 0.12}, {"density_per_m", 0.01}},
                            {{"genus", "altocumulus"}, {"base_altitude_m", 3500}, {"thickness_m", 600}, {"coverage", 0.15}, {"density_per_m", 0.004}}}};
const ApCase kSheetOverDeck{"a translucent sheet 10-20 km in front of a deck 30-60 km", 300.0, 6.0,
                            {{{"genus", "stratus"}, {"base_altitude_m", 1500}, {"thickness_m", 100}, {"coverage", 0.9},
                              {"density_per_m", 0.0006}, {"base_variation_m", 0}, {"casts_shadow", false}},
                             {{"genus", "stratocumulus"}, {"base_altitude_m", 4000}, {"thickness_m", 600}, {"coverage", 0.8}, {"density_per_m", 0.01}}}};

ApComparison compare_aerial_perspective(const ApCase& scene, const std::string& png, int width, int height) {
  const nlohmann::json clouds = {
      {"quality", "custom"}, {"temporal_upscaling", false}, {"resolution_scale", 1.0}, {"max_steps", 4096},
      {"min_step_m", 30.0}, {"max_step_m", 30.0}, {"step_growth", 0.0}, {"max_distance_m", 80000.0}, {"shadows", false},
      {"layers", scene.layers}};
  const nlohmann::json doc = {
      {"welkin_scene", 1},
      {"entities",
       {{{"name", "camera"}, {"components", {{"core.Camera", {{"position_m", {0, 0, scene.altitude_m}}, {"heading_deg", 30}, {"pitch_deg", scene.pitch_deg}, {"vertical_fov_deg", 30}, {"ev100", 14}}}}}},
        {{"name", "air"}, {"components", {{"atmosphere.Atmosphere", {{"mie_scattering", {0.021, 0.021, 0.021}}, {"mie_extinction", {0.0231, 0.0231, 0.0231}}}}}}},
        {{"name", "sun"}, {"components", {{"atmosphere.Sun", {{"azimuth_deg", 200}, {"elevation_deg", 25}}}}}},
        {{"name", "clouds"}, {"components", {{"clouds.VolumetricClouds", clouds}}}}}}};
  auto world = make_world();
  load_scene(*world, doc, "aerial perspective comparison");
  Renderer renderer(*world);
  auto& c = *world->registry().get<clouds::VolumetricClouds>(world->registry().first<clouds::VolumetricClouds>());
  auto frame = [&](clouds::CloudAerialPerspective mode, float coverage) {
    c.aerial_perspective = mode, c.coverage = coverage;
    renderer.render_frame({}, width, height);
    return std::pair{renderer.read_hdr(), renderer.read_output()};
  };
  const auto [along, along_ldr] = frame(clouds::CloudAerialPerspective::per_sample, 1.0f);
  const auto [mean, mean_ldr] = frame(clouds::CloudAerialPerspective::mean_depth, 1.0f);
  const auto [clear, clear_ldr] = frame(clouds::CloudAerialPerspective::per_sample, 0.0f);
  ApComparison r;
  ImageU8 sheet{3 * width, height, std::vector<uint8_t>(size_t(3) * width * height * 4, 255)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float a = along.pixel(x, y)[1], b = mean.pixel(x, y)[1], sky = clear.pixel(x, y)[1];
      double d = 0.0;
      if (std::abs(a - sky) > 0.02f * sky && a > 0.0f) {
        d = std::abs(b - a) / a;
        r.mean += d, r.worst = std::max(r.worst, d), ++r.cloud_pixels;
      }
      for (int k = 0; k < 4; ++k) {
        sheet.rgba[(size_t(y) * 3 * width + x) * 4 + size_t(k)] = along_ldr.pixel(x, y)[k];
        sheet.rgba[(size_t(y) * 3 * width + width + x) * 4 + size_t(k)] = mean_ldr.pixel(x, y)[k];
      }
      uint8_t* heat = &sheet.rgba[(size_t(y) * 3 * width + 2 * width + x) * 4];
      const double v = std::min(1.0, d * 10.0);
      heat[0] = uint8_t(255), heat[1] = heat[2] = uint8_t(255.0 * (1.0 - v));
    }
  r.mean /= std::max(r.cloud_pixels, 1);
  write_png(png, sheet);
  return r;
}

}  // namespace

// A scene's rays with their references and the probe that marches them.
RaySet measure_set(const std::string& scene, const std::string& rays, const CloudAccuracyOptions& o,
                   const clouds::reference::PathTraceSettings& settings) {
  RaySet set;
  set.measured = case_from_scene(scene);
  set.views = rays.empty() ? measured_views(o.quick) : read_rays(rays);
  set.name = (scene.empty() ? std::string("the built-in cumulus case") : scene) + (rays.empty() ? "" : " with " + rays);
  set.probe = std::make_unique<clouds::CloudProbe>(set.measured.clouds, set.measured.sun_azimuth_deg, set.measured.sun_elevation_deg);
  set.probe->set_reference_cache(o.cache.empty() ? DiskCache::from_environment() : DiskCache(o.cache));
  for (size_t i = 0; i < set.views.size(); ++i) {
    set.refs.push_back(set.probe->reference_radiance(set.views[i], settings));
    std::fprintf(stderr, "\rreference %zu/%zu", i + 1, set.views.size());
  }
  std::fprintf(stderr, "\n");
  return set;
}

int run_cloud_accuracy(const CloudAccuracyOptions& o) {
  int width = 0, height = 0;
  parse_size(o.size, width, height);
  const std::map<std::string, Quality> names{{"low", Quality::low}, {"medium", Quality::medium}, {"high", Quality::high}, {"ultra", Quality::ultra}};
  std::vector<CloudConfig> configs;
  for (MultipleScattering m : {MultipleScattering::diffusion, MultipleScattering::octaves})
    for (const std::string& q : o.qualities) {
      if (!names.count(q)) throw Error(ErrorInfo{.path = "--qualities", .expected = "low, medium, high or ultra", .found = "'" + q + "'"});
      configs.push_back({names.at(q), m, std::string(m == MultipleScattering::diffusion ? "diffusion" : "octaves") + "/" + q});
    }
  if (!o.image.empty()) return write_cloud_images(o, names, width, height);
  fs::create_directories(o.out);
  std::unique_ptr<GlContext> gl = create_headless_context();
  if (o.silhouettes_only) {
    report_silhouettes(o.ghosting_scene, o.quick ? 3 : 8, width / 2, height / 2);
    return kOk;
  }
  const std::string renderer = gl->info().renderer;
  // References once per ray (they do not depend on the GPU's settings).
  clouds::reference::PathTraceSettings settings;
  settings.samples = o.quick ? 1024 : 8192;
  // The rays measured (--scene, --rays) and, for --fit, the further sets (--fit-also).
  // The fit's options are checked before any ray is path traced (minutes a set).
  struct FitSet {
    std::string scene, rays;
    bool kept_back;
  };
  std::vector<FitSet> fit_sets;
  if (o.fit) {
    fit_candidate_terms(o);
    auto add_sets = [&](const std::vector<std::string>& pairs, const char* option, bool kept_back) {
      for (const std::string& also : pairs) {
        const size_t comma = also.find(',');
        if (comma == std::string::npos)
          throw Error(ErrorInfo{.path = option, .expected = "SCENE,RAYS (two files)", .found = "'" + also + "'"});
        fit_sets.push_back({also.substr(0, comma), also.substr(comma + 1), kept_back});
      }
    };
    add_sets(o.fit_also, "--fit-also", false);
    add_sets(o.fit_kept_back, "--fit-kept-back", true);
  }
  std::vector<RaySet> sets;
  sets.push_back(measure_set(o.scene, o.rays, o, settings));
  if (o.fit) {
    for (const FitSet& f : fit_sets) {
      sets.push_back(measure_set(f.scene, f.rays, o, settings));
      sets.back().kept_back = f.kept_back;
    }
    return fit_light_model(o, sets, names);
  }
  const MeasuredCase& measured = sets[0].measured;
  clouds::CloudProbe& probe = *sets[0].probe;
  const std::vector<CloudView>& views = sets[0].views;
  const std::vector<clouds::reference::CloudRadianceEstimate>& refs = sets[0].refs;

  std::ostringstream rays_csv, csv;  // written atomically once complete
  rays_csv << "config,view,altitude_m,heading_deg,pitch_deg,gpu,reference,reference_ci95,relative_error\n";
  csv << "config,clouds_ms,copy_ms,ratio_to_copy,relative_rmse,max_relative_error\n";
  std::map<MultipleScattering, PlotSeries> series;
  nlohmann::json results = nlohmann::json::array();
  // The cost is timed on the scene's view (--scene), else on the peer scene's.
  const CloudView cost_view =
      o.scene.empty() ? CloudView{"cost", 100.0, 210.0, 8.0}
                      : CloudView{"cost", measured.camera.position_m.z, measured.camera.heading_deg, measured.camera.pitch_deg,
                                  measured.camera.position_m.x, measured.camera.position_m.y};
  std::printf("errors relative to the mean reference radiance over the rays%s\n", o.light_only ? " (--light-only: not timed)" : "");
  std::printf("| model / quality | clouds ms | x copy | relative RMSE | worst |\n|---|---|---|---|---|\n");
  for (const CloudConfig& cfg : configs) {
    clouds::VolumetricClouds& c = probe.clouds();
    c.quality = cfg.quality;
    c.multiple_scattering = cfg.model;
    // Errors relative to the mean reference radiance: a ray that grazes a thin edge (a few percent of
    // the others' light, with a noisy reference) weighs what its light weighs.
    double mean_reference = 0.0;
    for (const auto& r : refs) mean_reference += r.radiance() / double(refs.size());
    double sum = 0.0, worst = 0.0;
    for (size_t i = 0; i < views.size(); ++i) {
      const double gpu = probe.gpu_radiance(views[i]), r = refs[i].radiance();
      const double e = (gpu - r) / mean_reference;
      sum += e * e, worst = std::max(worst, std::abs(e));
      rays_csv << cfg.name << "," << views[i].name << "," << views[i].altitude_m << "," << views[i].heading_deg << ","
               << views[i].pitch_deg << "," << gpu << "," << r << "," << refs[i].scattered.ci95 << "," << e << "\n";
    }
    const double rmse = std::sqrt(sum / double(views.size()));
    c.temporal_upscaling = true;
    // Frames that march: the view turns half a degree a frame (a still view keeps its clouds).
    const clouds::CloudProbe::Cost cost = o.light_only ? clouds::CloudProbe::Cost{0.0, 1.0} : probe.cost(cost_view, width, height, o.frames);
    c.temporal_upscaling = false;
    csv << cfg.name << "," << cost.clouds_ms << "," << cost.copy_ms << "," << cost.clouds_ms / cost.copy_ms << "," << rmse << "," << worst << "\n";
    std::printf("| %s | %.1f | %.0f | %.1f%% | %.1f%% |\n", cfg.name.c_str(), cost.clouds_ms, cost.clouds_ms / cost.copy_ms,
                100 * rmse, 100 * worst);
    PlotSeries& s = series[cfg.model];
    s.name = cfg.model == MultipleScattering::diffusion ? "diffusion" : "octaves";
    s.colour = cfg.model == MultipleScattering::diffusion ? glm::u8vec3(31, 119, 180) : glm::u8vec3(214, 39, 40);
    s.points.push_back({cost.clouds_ms, rmse, worst, cfg.name.substr(cfg.name.find('/') + 1)});
    results.push_back({{"config", cfg.name}, {"clouds_ms", cost.clouds_ms}, {"copy_ms", cost.copy_ms}, {"relative_rmse", rmse}, {"max", worst}});
  }
  write_term_budget(probe, views, refs, names, o, settings);
  write_sky_budget(probe, views, names, o, settings);
  write_file_atomically((fs::path(o.out) / "accuracy-clouds-rays.csv").string(), rays_csv.str());
  write_file_atomically((fs::path(o.out) / "accuracy-clouds.csv").string(), csv.str());
  if (o.light_only) return kOk;
  const std::string png = (fs::path(o.out) / "accuracy-clouds.png").string();
  write_error_plot(png, "welkin accuracy clouds: error against GPU time per frame",
                   "path-traced reference through the same field, " + std::to_string(views.size()) + " rays; " + o.size + ", " + renderer,
                   "GPU ms per frame, clouds passes (log)", {series[MultipleScattering::diffusion], series[MultipleScattering::octaves]});
  const Ghosting ghost = measure_ghosting(o.ghosting_scene, o.quick ? 8 : 20, width / 2, height / 2);
  report_silhouettes(o.ghosting_scene, o.quick ? 3 : 8, width / 2, height / 2);
  std::printf("\ntemporal upscaling on a flying, turning camera (peer scene, high), per-frame relative L1 against\n"
              "marching every pixel: clipped history %.2f%% mean, %.2f%% worst; plain reprojection %.2f%% mean, %.2f%% worst\n",
              100 * ghost.clipped_mean, 100 * ghost.clipped_worst, 100 * ghost.plain_mean, 100 * ghost.plain_worst);
  std::printf("aerial perspective at the clouds' mean depth against along the ray, hazy air:\n");
  for (const auto& [scene, file] : {std::pair{&kSparseClouds, "aerial-perspective-clouds.png"},
                                    std::pair{&kSheetOverDeck, "aerial-perspective-overlap.png"}}) {
    const std::string ap_png = (fs::path(o.out) / file).string();
    const ApComparison ap = compare_aerial_perspective(*scene, ap_png, o.quick ? 96 : 320, o.quick ? 54 : 180);
    std::printf("  %s (%d cloud pixels): %.2f%% mean, %.1f%% worst pixel; frames and difference in %s\n",
                scene->name, ap.cloud_pixels, 100 * ap.mean, 100 * ap.worst, ap_png.c_str());
  }
  if (o.json) std::printf("%s\n", nlohmann::json{{"rays", views.size()}, {"results", results}, {"plot", png}}.dump(2).c_str());
  std::printf("\nwrote %s, %s and %s\n", (fs::path(o.out) / "accuracy-clouds.csv").string().c_str(),
              (fs::path(o.out) / "accuracy-clouds-rays.csv").string().c_str(), png.c_str());
  return kOk;
}

}  // namespace welkin::cli
