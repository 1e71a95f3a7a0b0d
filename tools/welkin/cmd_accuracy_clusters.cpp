// welkin accuracy clusters [--scene SCENE] [--out DIR] [--size WxH] [--frames N] [--json]
// The mesh clusters' two errors, next to their GPU time as a ratio to a full-screen copy:
//  - the light's quadrature: each sample count against 16 samples (the converged limit of the same
//    puffs), luminance RMSE over the frame relative to the clouds' mean luminance;
//  - consistency with the volumetric path, the same layer drawn by each path alone, compared over the
//    pixels whose ray meets the layer's base within the hand-over band around near_m: the relative
//    difference of their mean luminance, and of the fraction of those pixels that show cloud (a
//    pixel shows cloud where it differs from the clear sky by more than 5%: a proxy for alpha).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
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
constexpr const char* kClusters = "clouds.CloudClusters";
int doc_cluster_layer = 0;  // the layer the scene's clusters draw (set before loading)

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

struct SceneRender {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
};

// The scene with its clusters set by `assignments`, or without the components named in `drop`.
SceneRender load(nlohmann::json doc, const std::string& file, const std::vector<std::string>& drop,
                 const std::vector<std::string>& assignments) {
  for (auto& e : doc["entities"]) {
    for (const std::string& d : drop) e["components"].erase(d);
    // The clusters' layer alone (soloed): the other layers would count as cloud cover for both paths.
    auto& c = e["components"];
    if (c.contains("clouds.VolumetricClouds") && c["clouds.VolumetricClouds"].contains("layers")) {
      const int layer = doc_cluster_layer;
      auto& layers = c["clouds.VolumetricClouds"]["layers"];
      if (layers.is_array() && layers.size() > size_t(layer)) layers[size_t(layer)]["solo"] = true;
    }
  }
  SceneRender s{make_world(), nullptr};
  load_scene(*s.world, doc, file);
  for (const std::string& a : assignments) apply_assignment(*s.world, std::string(kClusters) + "/" + a);
  s.renderer = std::make_unique<Renderer>(*s.world);
  return s;
}

ImageF still(SceneRender& s, int width, int height) { return render_still(*s.renderer, width, height); }
std::pair<double, double> cost(SceneRender& s, int width, int height, int frames) {
  return passes_cost(*s.renderer, "clouds.clusters_", width, height, frames);
}

}  // namespace

int run_cluster_accuracy(const ClusterAccuracyOptions& o) {
  int width = 0, height = 0;
  parse_size(o.size, width, height);
  const nlohmann::json doc = read_json_file(o.scene);
  const nlohmann::json* settings = nullptr;
  if (doc.contains("entities") && doc["entities"].is_array())
    for (const auto& e : doc["entities"])
      if (e.contains("components") && e["components"].contains(kClusters)) settings = &e["components"][kClusters];
  if (!settings)
    throw Error(ErrorInfo{.file = o.scene, .expected = "a scene with a clouds.CloudClusters component", .found = "none"});
  doc_cluster_layer = settings->value("layer", 0);
  fs::create_directories(o.out);
  std::unique_ptr<GlContext> gl = create_headless_context();
  const std::string renderer = gl->info().renderer;

  // The clear sky, the volumetric path alone, and the clusters alone out to their far distance.
  SceneRender clear_scene = load(doc, o.scene, {"clouds.VolumetricClouds", kClusters}, {});
  const ImageF clear = still(clear_scene, width, height);
  SceneRender volumetric_scene = load(doc, o.scene, {kClusters}, {});
  const ImageF volumetric = still(volumetric_scene, width, height);
  SceneRender clusters_scene = load(doc, o.scene, {}, {"near_m=0", "crossfade_m=0", "samples=16"});
  const ImageF clusters = still(clusters_scene, width, height);
  const ImageF reference = [&] {
    SceneRender s = load(doc, o.scene, {}, {"samples=16"});
    return still(s, width, height);
  }();

  // The pixels whose ray meets the layer's base within the hand-over band.
  World& world = *clusters_scene.world;
  const Entity ce = world.registry().first<Camera>();
  const FrameView view = make_frame_view(*world.registry().get<Camera>(ce), width, height);
  const double near_m = settings->value("near_m", 8000.0), crossfade_m = settings->value("crossfade_m", 2000.0);
  double base_m = 1500.0;
  for (const auto& e : doc["entities"])
    if (e["components"].contains("clouds.VolumetricClouds")) {
      const auto& v = e["components"]["clouds.VolumetricClouds"];
      const int layer = settings->value("layer", 0);
      if (v.contains("layers") && v["layers"].size() > size_t(layer)) base_m = v["layers"][size_t(layer)].value("base_altitude_m", 1500.0);
    }
  const double planet_m = 6360000.0, camera_r = planet_m + view.camera_position_m.z, base_r = planet_m + base_m;
  const double band_lo = std::max(near_m - crossfade_m, 0.0), band_hi = near_m + crossfade_m;
  double sum_v = 0.0, sum_c = 0.0, abs_diff = 0.0;
  int band = 0, cloudy_v = 0, cloudy_c = 0, cloudy_either_differ = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 d = glm::dvec3(pixel_direction(view, x + 0.5, y + 0.5));
      const double b = camera_r * d.z, disc = b * b - (camera_r * camera_r - base_r * base_r);
      if (disc < 0.0) continue;
      const double t = -b + std::sqrt(disc);  // from below the base: where the ray rises through it
      if (!(t >= band_lo && t <= band_hi)) continue;
      const size_t i = (size_t(y) * size_t(width) + size_t(x)) * 4;  // rows top down, as pixel_direction's y
      const double yv = luminance(&volumetric.rgba[i]), yc = luminance(&clusters.rgba[i]), y0 = luminance(&clear.rgba[i]);
      ++band;
      sum_v += yv, sum_c += yc, abs_diff += std::abs(yc - yv);
      const bool cv = std::abs(yv - y0) > 0.05 * y0, cc = std::abs(yc - y0) > 0.05 * y0;
      cloudy_v += cv, cloudy_c += cc, cloudy_either_differ += cv != cc;
    }
  if (band == 0)
    throw Error(ErrorInfo{.file = o.scene, .expected = "a view in which some rays meet the layer's base within the hand-over band",
                          .found = "none"});
  const double mean_v = sum_v / band, mean_c = sum_c / band;
  const double luminance_difference = (mean_c - mean_v) / mean_v, pixel_difference = abs_diff / sum_v;
  const double cover_v = double(cloudy_v) / band, cover_c = double(cloudy_c) / band, cover_mismatch = double(cloudy_either_differ) / band;
  std::printf("consistency at the switch (%d pixels whose ray meets the layer's base %.0f-%.0f m away):\n", band, band_lo, band_hi);
  std::printf("  mean luminance: volumetric %.4g, clusters %.4g: %+.1f%%; per pixel |difference| %.1f%% of the mean\n", mean_v, mean_c,
              100.0 * luminance_difference, 100.0 * pixel_difference);
  std::printf("  cloud cover (differs from the clear sky by > 5%%): volumetric %.1f%%, clusters %.1f%%; pixels covered by one path only %.1f%%\n",
              100.0 * cover_v, 100.0 * cover_c, 100.0 * cover_mismatch);

  // The light's quadrature against 16 samples, with the clusters' GPU time.
  double clouds_mean = 0.0;
  const size_t pixels = size_t(width) * height;
  for (size_t i = 0; i < pixels; ++i) clouds_mean += std::abs(luminance(&reference.rgba[i * 4]) - luminance(&clear.rgba[i * 4])) / double(pixels);
  std::ostringstream csv;
  csv << "samples,clusters_ms,copy_ms,ratio_to_copy,relative_rmse\n";
  nlohmann::json results = nlohmann::json::array();
  std::printf("\nthe light's quadrature against 16 samples (luminance RMSE over the frame, relative to the clouds' mean difference from the clear sky)\n");
  std::printf("| samples | clusters ms | x copy | RMSE |\n|---|---|---|---|\n");
  for (int samples : {1, 2, 3, 4, 8}) {
    SceneRender s = load(doc, o.scene, {}, {"samples=" + std::to_string(samples)});
    const ImageF img = still(s, width, height);
    double sq = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
      const double e = luminance(&img.rgba[i * 4]) - luminance(&reference.rgba[i * 4]);
      sq += e * e;
    }
    const double rmse = std::sqrt(sq / double(pixels)) / clouds_mean;
    const auto [ms, copy_ms] = cost(s, width, height, o.frames);
    std::printf("| %d | %.2f | %.1f | %.2f%% |\n", samples, ms, ms / copy_ms, 100.0 * rmse);
    csv << samples << "," << ms << "," << copy_ms << "," << ms / copy_ms << "," << rmse << "\n";
    results.push_back({{"samples", samples}, {"clusters_ms", ms}, {"copy_ms", copy_ms}, {"relative_rmse", rmse}});
  }
  write_file_atomically((fs::path(o.out) / "accuracy-clusters.csv").string(), csv.str());
  if (o.json)
    std::printf("%s\n", nlohmann::json{{"band_pixels", band},
                                       {"mean_luminance_difference", luminance_difference},
                                       {"pixel_luminance_difference", pixel_difference},
                                       {"cover_volumetric", cover_v},
                                       {"cover_clusters", cover_c},
                                       {"cover_mismatch", cover_mismatch},
                                       {"quadrature", results}}
                            .dump(2)
                            .c_str());
  std::printf("\nwrote %s (%s, %s)\n", (fs::path(o.out) / "accuracy-clusters.csv").string().c_str(), o.size.c_str(), renderer.c_str());
  return kOk;
}

}  // namespace welkin::cli
