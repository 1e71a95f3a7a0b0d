// welkin accuracy clusters|billboards [--scene SCENE] [--out DIR] [--size WxH] [--frames N] [--json]
// The errors of the cheaper cloud paths, next to their GPU time as a ratio to a full-screen copy.
// Both report their consistency with the volumetric path: the same layer drawn by each path alone,
// compared over the pixels whose ray meets the layer's base within the band around the switch
// distance: the relative difference of their mean luminance, and of the fraction of those pixels
// that show cloud (a pixel shows cloud where it differs from the clear sky by more than 5%: a proxy
// for alpha). And each its own:
//  - clusters: the light's quadrature, each sample count against 16 samples (the converged limit of
//    the same puffs), luminance RMSE over the frame relative to the clouds' mean luminance;
//  - billboards: the impostor against its reference (each pixel marched through the same baked
//    archetype and lit through a march), for several atlas sizes and view grids.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "comparison_panels.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

struct SceneRender {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
};

// The scene and the settings of the path measured (`component`, drawing one layer of the clouds).
struct PathScene {
  nlohmann::json doc;
  std::string file, component;
  const nlohmann::json* settings = nullptr;
  int layer = 0;
};
PathScene read_path_scene(const std::string& file, const std::string& component) {
  PathScene p{read_json_file(file), file, component};
  if (p.doc.contains("entities") && p.doc["entities"].is_array())
    for (const auto& e : p.doc["entities"])
      if (e.contains("components") && e["components"].contains(component)) p.settings = &e["components"][component];
  if (!p.settings) throw Error(ErrorInfo{.file = file, .expected = "a scene with a " + component + " component", .found = "none"});
  p.layer = p.settings->value("layer", 0);
  return p;
}

// The scene with the path's component set by `assignments`, or without the components named in `drop`.
SceneRender load(const PathScene& p, const std::vector<std::string>& drop, const std::vector<std::string>& assignments) {
  nlohmann::json doc = p.doc;
  for (auto& e : doc["entities"]) {
    for (const std::string& d : drop) e["components"].erase(d);
    // The path's layer alone (soloed): the other layers would count as cloud cover for both paths.
    auto& c = e["components"];
    if (c.contains("clouds.VolumetricClouds") && c["clouds.VolumetricClouds"].contains("layers")) {
      auto& layers = c["clouds.VolumetricClouds"]["layers"];
      if (layers.is_array() && layers.size() > size_t(p.layer)) layers[size_t(p.layer)]["solo"] = true;
    }
  }
  SceneRender s{make_world(), nullptr};
  load_scene(*s.world, doc, p.file);
  for (const std::string& a : assignments) apply_assignment(*s.world, p.component + "/" + a);
  s.renderer = std::make_unique<Renderer>(*s.world);
  return s;
}

ImageF still(SceneRender& s, int width, int height) { return render_still(*s.renderer, width, height); }

// The volumetric path and another drawing the same layer, over the pixels whose ray meets the
// layer's base between band_lo and band_hi metres.
struct Consistency {
  int band = 0;
  double luminance_difference = 0.0, pixel_difference = 0.0;  // relative to the volumetric path's mean
  double cover_volumetric = 0.0, cover_path = 0.0, cover_mismatch = 0.0;
};
Consistency consistency_at_switch(const PathScene& p, const SceneRender& scene, int width, int height, double band_lo,
                                  double band_hi, const ImageF& clear, const ImageF& volumetric, const ImageF& path,
                                  const std::string& png) {
  World& world = *scene.world;
  const Entity ce = world.registry().first<Camera>();
  const FrameView view = make_frame_view(*world.registry().get<Camera>(ce), width, height);
  double base_m = 1500.0;
  for (const auto& e : p.doc["entities"])
    if (e["components"].contains("clouds.VolumetricClouds")) {
      const auto& v = e["components"]["clouds.VolumetricClouds"];
      if (v.contains("layers") && v["layers"].size() > size_t(p.layer)) base_m = v["layers"][size_t(p.layer)].value("base_altitude_m", 1500.0);
    }
  const double planet_m = 6360000.0, camera_r = planet_m + view.camera_position_m.z, base_r = planet_m + base_m;
  double sum_v = 0.0, sum_c = 0.0, abs_diff = 0.0;
  int cloudy_v = 0, cloudy_c = 0, cloudy_either_differ = 0;
  Consistency c;
  // The picture: the path above the volumetric path, their difference below (outside the band: none).
  ComparisonPanels panels{width, height};
  std::vector<size_t> in_band;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 d = glm::dvec3(pixel_direction(view, x + 0.5, y + 0.5));
      const double b = camera_r * d.z, disc = b * b - (camera_r * camera_r - base_r * base_r);
      if (disc < 0.0) continue;
      const double t = -b + std::sqrt(disc);  // from below the base: where the ray rises through it
      if (!(t >= band_lo && t <= band_hi)) continue;
      const size_t i = (size_t(y) * size_t(width) + size_t(x)) * 4;  // rows top down, as pixel_direction's y
      in_band.push_back(i / 4);
      const double yv = luminance(&volumetric.rgba[i]), yc = luminance(&path.rgba[i]), y0 = luminance(&clear.rgba[i]);
      ++c.band;
      sum_v += yv, sum_c += yc, abs_diff += std::abs(yc - yv);
      const bool cv = std::abs(yv - y0) > 0.05 * y0, cc = std::abs(yc - y0) > 0.05 * y0;
      cloudy_v += cv, cloudy_c += cc, cloudy_either_differ += cv != cc;
    }
  if (c.band == 0)
    throw Error(ErrorInfo{.file = p.file, .expected = "a view in which some rays meet the layer's base within the hand-over band",
                          .found = "none"});
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
    panels.approximation.emplace_back(path.rgba[i * 4], path.rgba[i * 4 + 1], path.rgba[i * 4 + 2]);
    panels.reference.emplace_back(volumetric.rgba[i * 4], volumetric.rgba[i * 4 + 1], volumetric.rgba[i * 4 + 2]);
    panels.relative.push_back(0.0);
  }
  for (size_t i : in_band)
    panels.relative[i] = (luminance(&path.rgba[i * 4]) - luminance(&volumetric.rgba[i * 4])) / (sum_v / c.band);
  write_comparison_panels(png, panels, 2, 1.0);
  c.luminance_difference = (sum_c - sum_v) / sum_v;
  c.pixel_difference = abs_diff / sum_v;
  c.cover_volumetric = double(cloudy_v) / c.band, c.cover_path = double(cloudy_c) / c.band;
  c.cover_mismatch = double(cloudy_either_differ) / c.band;
  std::printf("consistency at the switch (%d pixels whose ray meets the layer's base %.0f-%.0f m away):\n", c.band, band_lo, band_hi);
  std::printf("  mean luminance: %+.1f%% against the volumetric path; per pixel |difference| %.1f%% of its mean\n",
              100.0 * c.luminance_difference, 100.0 * c.pixel_difference);
  std::printf("  cloud cover (differs from the clear sky by > 5%%): volumetric %.1f%%, %s %.1f%%; pixels covered by one path only %.1f%%\n",
              100.0 * c.cover_volumetric, p.component.c_str(), 100.0 * c.cover_path, 100.0 * c.cover_mismatch);
  return c;
}
nlohmann::json to_json(const Consistency& c) {
  return {{"band_pixels", c.band},
          {"mean_luminance_difference", c.luminance_difference},
          {"pixel_luminance_difference", c.pixel_difference},
          {"cover_volumetric", c.cover_volumetric},
          {"cover_path", c.cover_path},
          {"cover_mismatch", c.cover_mismatch}};
}

// Luminance RMSE of `image` against `reference`, relative to the clouds' mean difference from the clear sky.
double relative_rmse(const ImageF& image, const ImageF& reference, const ImageF& clear) {
  const size_t pixels = reference.rgba.size() / 4;
  double clouds_mean = 0.0, sq = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    clouds_mean += std::abs(luminance(&reference.rgba[i * 4]) - luminance(&clear.rgba[i * 4])) / double(pixels);
    const double e = luminance(&image.rgba[i * 4]) - luminance(&reference.rgba[i * 4]);
    sq += e * e;
  }
  return std::sqrt(sq / double(pixels)) / std::max(clouds_mean, 1e-30);
}
}  // namespace

// What both commands start with: the scene, the size, a GL context and the clear sky.
struct PathRun {
  PathScene p;
  int width = 0, height = 0;
  std::unique_ptr<GlContext> gl;
  std::string renderer;
  ImageF clear;
};
PathRun start_path_run(const std::string& scene, const std::string& component, const std::string& size, const std::string& out) {
  PathRun run{read_path_scene(scene, component)};
  parse_size(size, run.width, run.height);
  fs::create_directories(out);
  run.gl = create_headless_context();
  run.renderer = run.gl->info().renderer;
  SceneRender clear_scene = load(run.p, {"clouds.VolumetricClouds", component}, {});
  run.clear = still(clear_scene, run.width, run.height);
  return run;
}

int run_cluster_accuracy(const ClusterAccuracyOptions& o) {
  const PathRun run = start_path_run(o.scene, "clouds.CloudClusters", o.size, o.out);
  const PathScene& p = run.p;
  const int width = run.width, height = run.height;
  const ImageF& clear = run.clear;
  const std::string& renderer = run.renderer;

  // The volumetric path alone, and the clusters alone out to their far distance, as the scene sets
  // them (their samples are the steps of their march through the field).
  SceneRender volumetric_scene = load(p, {p.component}, {});
  const ImageF volumetric = still(volumetric_scene, width, height);
  SceneRender clusters_scene = load(p, {}, {"near_m=0", "crossfade_m=0"});
  const ImageF clusters = still(clusters_scene, width, height);
  const ImageF reference = [&] {
    SceneRender s = load(p, {}, {"samples=16"});
    return still(s, width, height);
  }();
  const double near_m = p.settings->value("near_m", 8000.0), crossfade_m = p.settings->value("crossfade_m", 2000.0);
  const Consistency switch_figures = consistency_at_switch(p, clusters_scene, width, height, std::max(near_m - crossfade_m, 0.0),
                                                           near_m + crossfade_m, clear, volumetric, clusters,
                                                           (fs::path(o.out) / "switch-clusters.png").string());

  // The light's quadrature against 16 samples, with the clusters' GPU time.
  std::ostringstream csv;
  csv << "samples,clusters_ms,copy_ms,ratio_to_copy,relative_rmse\n";
  nlohmann::json results = nlohmann::json::array();
  std::printf("\nthe light's quadrature against 16 samples (luminance RMSE over the frame, relative to the clouds' mean difference from the clear sky)\n");
  std::printf("| samples | clusters ms | x copy | RMSE |\n|---|---|---|---|\n");
  for (int samples : o.quick ? std::vector<int>{3} : std::vector<int>{1, 2, 3, 4, 8}) {
    SceneRender s = load(p, {}, {"samples=" + std::to_string(samples)});
    const double rmse = relative_rmse(still(s, width, height), reference, clear);
    const auto [ms, copy_ms] = passes_cost(*s.renderer, "clouds.clusters_", width, height, o.frames);
    std::printf("| %d | %.2f | %.1f | %.2f%% |\n", samples, ms, ms / copy_ms, 100.0 * rmse);
    csv << samples << "," << ms << "," << copy_ms << "," << ms / copy_ms << "," << rmse << "\n";
    results.push_back({{"samples", samples}, {"clusters_ms", ms}, {"copy_ms", copy_ms}, {"relative_rmse", rmse}});
  }
  write_file_atomically((fs::path(o.out) / "accuracy-clusters.csv").string(), csv.str());
  if (o.json) {
    nlohmann::json j = to_json(switch_figures);
    j["quadrature"] = results;
    std::printf("%s\n", j.dump(2).c_str());
  }
  std::printf("\nwrote %s (%s, %s)\n", (fs::path(o.out) / "accuracy-clusters.csv").string().c_str(), o.size.c_str(), renderer.c_str());
  return kOk;
}

int run_billboard_accuracy(const BillboardAccuracyOptions& o) {
  const PathRun run = start_path_run(o.scene, "clouds.CloudBillboards", o.size, o.out);
  const PathScene& p = run.p;
  const int width = run.width, height = run.height;
  const ImageF& clear = run.clear;
  const std::string& renderer = run.renderer;

  // The impostor against its reference, the same archetypes marched, over atlas sizes and view grids.
  struct Grid {
    int resolution, azimuths, elevations;
  };
  const std::vector<Grid> grids = o.quick ? std::vector<Grid>{{16, 8, 5}, {32, 8, 5}}
                                          : std::vector<Grid>{{16, 8, 5}, {32, 4, 1}, {32, 8, 1}, {32, 8, 3}, {32, 8, 5}, {32, 8, 8}, {32, 16, 5}, {64, 8, 5}};
  std::ostringstream csv;
  csv << "resolution,azimuths,elevations,billboards_ms,reference_ms,copy_ms,ratio_to_copy,relative_rmse,mean_luminance_difference\n";
  nlohmann::json results = nlohmann::json::array();
  std::printf("the impostor against the reference (each pixel marched through the same archetypes): luminance RMSE over the frame "
              "relative to the clouds' mean difference from the clear sky, and the difference of the mean\n");
  std::printf("| atlas texels | views (azimuths x elevations) | billboards ms | x copy | reference x copy | RMSE | mean |\n"
              "|---|---|---|---|---|---|---|\n");
  for (const Grid& g : grids) {
    const std::vector<std::string> grid = {"atlas_resolution=" + std::to_string(g.resolution), "view_azimuths=" + std::to_string(g.azimuths),
                                           "view_elevations=" + std::to_string(g.elevations)};
    SceneRender impostor = load(p, {}, grid);
    std::vector<std::string> volume = grid;
    volume.push_back("render=\"volume\"");
    SceneRender reference = load(p, {}, volume);
    const ImageF a = still(impostor, width, height), r = still(reference, width, height);
    const double rmse = relative_rmse(a, r, clear);
    double sum_a = 0.0, sum_r = 0.0;
    for (size_t i = 0; i < a.rgba.size() / 4; ++i)
      sum_a += luminance(&a.rgba[i * 4]) - luminance(&clear.rgba[i * 4]), sum_r += luminance(&r.rgba[i * 4]) - luminance(&clear.rgba[i * 4]);
    const double mean_difference = (sum_a - sum_r) / std::max(std::abs(sum_r), 1e-30);
    const auto [ms, copy_ms] = passes_cost(*impostor.renderer, "clouds.billboards_", width, height, o.frames);
    const auto [reference_ms, copy2_ms] = passes_cost(*reference.renderer, "clouds.billboards_", width, height, o.frames);
    std::printf("| %d | %d x %d | %.2f | %.1f | %.1f | %.1f%% | %+.1f%% |\n", g.resolution, g.azimuths, g.elevations, ms, ms / copy_ms,
                reference_ms / copy2_ms, 100.0 * rmse, 100.0 * mean_difference);
    csv << g.resolution << "," << g.azimuths << "," << g.elevations << "," << ms << "," << reference_ms << "," << copy_ms << ","
        << ms / copy_ms << "," << rmse << "," << mean_difference << "\n";
    results.push_back({{"resolution", g.resolution}, {"azimuths", g.azimuths}, {"elevations", g.elevations}, {"billboards_ms", ms},
                       {"reference_ms", reference_ms}, {"copy_ms", copy_ms}, {"relative_rmse", rmse},
                       {"mean_luminance_difference", mean_difference}});
  }

  // Consistency with the volumetric path where the billboards take over (at near_m).
  SceneRender volumetric_scene = load(p, {p.component}, {});
  const ImageF volumetric = still(volumetric_scene, width, height);
  SceneRender billboards_scene = load(p, {}, {"near_m=0", "crossfade_m=0"});
  const ImageF billboards = still(billboards_scene, width, height);
  const double near_m = p.settings->value("near_m", 25000.0), crossfade_m = p.settings->value("crossfade_m", 3000.0);
  std::printf("\n");
  const Consistency switch_figures = consistency_at_switch(p, billboards_scene, width, height, std::max(near_m - crossfade_m, 0.0),
                                                           near_m + crossfade_m, clear, volumetric, billboards,
                                                           (fs::path(o.out) / "switch-billboards.png").string());
  const std::string csv_file = (fs::path(o.out) / "accuracy-billboards.csv").string();
  write_file_atomically(csv_file, csv.str());
  if (o.json) {
    nlohmann::json j = to_json(switch_figures);
    j["impostor"] = results;
    std::printf("%s\n", j.dump(2).c_str());
  }
  std::printf("\nwrote %s (%s, %s)\n", csv_file.c_str(), o.size.c_str(), renderer.c_str());
  return kOk;
}

}  // namespace welkin::cli
