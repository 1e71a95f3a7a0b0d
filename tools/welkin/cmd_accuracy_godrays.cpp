// welkin accuracy godrays [--scene SCENE] [--out DIR] [--size WxH] [--frames N] [--quick] [--json]
// The god rays' "error against run time": each method and setting renders the scene's frame, and the
// light its shafts take away is compared with a reference march of the same scene (every pixel, 512
// samples at the steps' midpoints: the converged limit of the marched estimate), next to the GPU time
// of the shafts' passes as a ratio to a full-screen copy measured in the same run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "error_plot.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;
constexpr const char* kComponent = "godrays.GodRays";

struct ShaftConfig {
  std::string method;  // marched or screen_space
  int divisor = 4, steps = 16;  // steps: marched samples, or screen-space taps
  std::string name() const { return method + " 1/" + std::to_string(divisor) + " " + std::to_string(steps); }
};

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// A world of the scene, without its god rays or with them set to `assignments`.
struct SceneRender {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
};
SceneRender load(const nlohmann::json& doc, const std::string& file, const std::vector<std::string>& assignments) {
  SceneRender s{make_world(), nullptr};
  load_scene(*s.world, doc, file);
  for (const std::string& a : assignments) apply_assignment(*s.world, std::string(kComponent) + "/" + a);
  s.renderer = std::make_unique<Renderer>(*s.world);
  return s;
}

ImageF still(SceneRender& s, int width, int height) { return render_still(*s.renderer, width, height); }
std::pair<double, double> cost(SceneRender& s, int width, int height, int frames) {
  return passes_cost(*s.renderer, "godrays.", width, height, frames);
}

// The shafts' light (what the frame without god rays holds more) as a grey image, scaled so that the
// reference's brightest shaft is white.
void write_shafts_png(const std::string& path, const ImageF& without, const ImageF& with, double peak) {
  ImageU8 out;
  out.width = without.width, out.height = without.height;
  out.rgba.resize(size_t(out.width) * out.height * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const double v = std::clamp((luminance(without.pixel(x, y)) - luminance(with.pixel(x, y))) / peak, 0.0, 1.0);
      uint8_t* o = &out.rgba[(size_t(y) * out.width + x) * 4];
      o[0] = o[1] = o[2] = uint8_t(std::lround(255.0 * std::sqrt(v)));  // sqrt: faint shafts show
      o[3] = 255;
    }
  write_png(path, out);
}

}  // namespace

int run_god_ray_accuracy(const GodRayAccuracyOptions& o) {
  int width = 0, height = 0;
  parse_size(o.size, width, height);
  const nlohmann::json doc = read_json_file(o.scene);
  // The scene without god rays: what the shafts are measured from.
  nlohmann::json bare = doc;
  if (bare.contains("entities") && bare["entities"].is_array())
    for (auto& e : bare["entities"])
      if (e.contains("components") && e["components"].is_object()) e["components"].erase(kComponent);
  fs::create_directories(o.out);
  std::unique_ptr<GlContext> gl = create_headless_context();
  const std::string renderer = gl->info().renderer;

  const ImageF without = [&] {
    SceneRender s = load(bare, o.scene, {});
    return still(s, width, height);
  }();
  const ImageF reference = [&] {
    SceneRender s = load(doc, o.scene, {"method=marched", "resolution_divisor=1", "steps=512", "jitter=false"});
    return still(s, width, height);
  }();
  const size_t pixels = size_t(width) * height;
  double shaft_sq = 0.0, shaft_mean = 0.0, peak = 0.0, mean_light = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    const double l = luminance(&without.rgba[i * 4]) - luminance(&reference.rgba[i * 4]);
    shaft_sq += l * l, shaft_mean += l / double(pixels), peak = std::max(peak, l);
    mean_light += luminance(&without.rgba[i * 4]) / double(pixels);
  }
  const double shaft_rms = std::sqrt(shaft_sq / double(pixels));
  if (!(shaft_rms > 0.0))
    throw Error(ErrorInfo{.file = o.scene, .expected = "a scene whose god rays take light away (a sun, something casting shadows)",
                          .found = "no shafts in the reference"});
  write_shafts_png((fs::path(o.out) / "godrays-reference.png").string(), without, reference, peak);

  std::vector<ShaftConfig> configs;
  for (int d : {4, 2})
    for (int steps : o.quick ? std::vector<int>{16} : std::vector<int>{8, 16, 32}) configs.push_back({"marched", d, steps});
  for (int d : {8, 4})
    for (int taps : o.quick ? std::vector<int>{16} : std::vector<int>{8, 16, 32}) configs.push_back({"screen_space", d, taps});

  std::ostringstream csv;
  csv << "method,resolution_divisor,steps,godrays_ms,copy_ms,ratio_to_copy,shaft_relative_rmse,worst_block,image_relative_rmse\n";
  std::map<std::string, PlotSeries> series;
  nlohmann::json results = nlohmann::json::array();
  std::printf("shafts: %.4g mean luminance taken away (%.2f%% of the frame's), RMS %.4g, peak %.4g\n", shaft_mean,
              100.0 * shaft_mean / mean_light, shaft_rms, peak);
  std::printf("errors against the reference march (per pixel, luminance): of the shafts' light, relative to its RMS\n"
              "(over the frame and over its worst 8x8 block); of the image, relative to its mean\n");
  std::printf("| method | resolution | steps or taps | godrays ms | x copy | shafts RMSE | worst 8x8 block | image RMSE |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const ShaftConfig& c : configs) {
    std::vector<std::string> set = {"method=" + c.method, "resolution_divisor=" + std::to_string(c.divisor)};
    set.push_back((c.method == "marched" ? "steps=" : "screen_samples=") + std::to_string(c.steps));
    SceneRender s = load(doc, o.scene, set);
    const ImageF img = still(s, width, height);
    // Over the frame, and the worst 8x8 block (where the shafts are wrong, not only noisy).
    double err_sq = 0.0;
    std::map<std::pair<int, int>, std::pair<double, int>> blocks;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double e = luminance(img.pixel(x, y)) - luminance(reference.pixel(x, y));
        err_sq += e * e;
        auto& b = blocks[{x / 8, y / 8}];
        b.first += e * e, ++b.second;
      }
    const double rmse = std::sqrt(err_sq / double(pixels));
    double worst_block = 0.0;
    for (const auto& [k, b] : blocks) worst_block = std::max(worst_block, std::sqrt(b.first / b.second));
    const auto [ms, copy_ms] = cost(s, width, height, o.frames);
    const double shaft_error = rmse / shaft_rms, image_error = rmse / mean_light, worst = worst_block / shaft_rms;
    csv << c.method << "," << c.divisor << "," << c.steps << "," << ms << "," << copy_ms << "," << ms / copy_ms << ","
        << shaft_error << "," << worst << "," << image_error << "\n";
    std::printf("| %s | 1/%d | %d | %.2f | %.1f | %.1f%% | %.0f%% | %.3f%% |\n", c.method.c_str(), c.divisor, c.steps, ms, ms / copy_ms,
                100 * shaft_error, 100 * worst, 100 * image_error);
    PlotSeries& p = series[c.method + std::to_string(c.divisor)];
    p.name = c.method + " 1/" + std::to_string(c.divisor);
    p.colour = c.method == "marched" ? (c.divisor == 4 ? glm::u8vec3(31, 119, 180) : glm::u8vec3(23, 190, 207))
                                     : (c.divisor == 8 ? glm::u8vec3(214, 39, 40) : glm::u8vec3(255, 127, 14));
    p.points.push_back({ms, shaft_error, worst, std::to_string(c.steps)});
    results.push_back({{"method", c.method}, {"resolution_divisor", c.divisor}, {"steps", c.steps}, {"godrays_ms", ms},
                       {"copy_ms", copy_ms}, {"shaft_relative_rmse", shaft_error}, {"worst_block", worst}, {"image_relative_rmse", image_error}});
    if (c.steps == 16 || c.steps == 32)
      write_shafts_png((fs::path(o.out) / ("godrays-" + c.method + "-" + std::to_string(c.divisor) + "-" + std::to_string(c.steps) + ".png")).string(),
                       without, img, peak);
  }
  write_file_atomically((fs::path(o.out) / "accuracy-godrays.csv").string(), csv.str());
  const std::string png = (fs::path(o.out) / "accuracy-godrays.png").string();
  std::vector<PlotSeries> plotted;
  for (auto& [k, s] : series) plotted.push_back(s);
  write_error_plot(png, "welkin accuracy godrays: error against GPU time per frame",
                   "reference march (every pixel, 512 samples), " + o.scene + "; " + o.size + ", " + renderer,
                   "GPU ms per frame, god-ray passes (log)", plotted);
  if (o.json) std::printf("%s\n", nlohmann::json{{"shaft_rms", shaft_rms}, {"results", results}, {"plot", png}}.dump(2).c_str());
  std::printf("\nwrote %s, %s and the shafts' images (godrays-*.png, white: the reference's brightest shaft)\n",
              (fs::path(o.out) / "accuracy-godrays.csv").string().c_str(), png.c_str());
  return kOk;
}

}  // namespace welkin::cli
