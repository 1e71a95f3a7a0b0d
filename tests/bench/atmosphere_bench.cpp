// Atmosphere benchmarks at 640x360, every frame forced to completion: the LUT path (Hillaire 2020)
// against the per-pixel nested raymarch (24 primary x 8 light steps: method raymarch at the default
// quality, high; the seeds' approach), and the sky pass against a full-screen RGBA16F copy of the same
// size (the floor of any full-screen pass), each ratio from one run. The scene is the sky alone:
// camera on the ground looking 10 degrees up, sun 30 degrees high, no geometry.
//
//   welkin_atmosphere_bench --benchmark_counters_tabular=true
//
// Counters are milliseconds per frame (medians over the iterations) and ratios: *_x_copy against the
// copy, speedup_* the raymarch's cost over the LUT path's. Errors of the same configurations against
// the references come from `welkin accuracy atmosphere` (docs/atmosphere.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "welkin/atmosphere/gpu.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/scene_file.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
}

namespace {

using namespace welkin;

constexpr int kW = 640, kH = 360;

GlContext& gl() {
  static std::unique_ptr<GlContext> ctx = create_headless_context();
  return *ctx;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// A world rendering the sky alone with one method and quality preset.
struct Sky {
  std::unique_ptr<World> world;
  std::unique_ptr<Renderer> renderer;
  uint64_t frame = 0;

  Sky(const std::string& method, const std::string& quality) {
    gl();
    world = std::make_unique<World>();
    world->modules().add_static(welkin::modules::atmosphere_module());
    const nlohmann::json doc = {
        {"welkin_scene", 1},
        {"entities",
         {{{"name", "sky"},
           {"components",
            {{"core.Camera", {{"pitch_deg", 10}, {"heading_deg", 0}, {"vertical_fov_deg", 60}}},
             {"atmosphere.Atmosphere", {{"method", method}, {"quality", quality}}},
             {"atmosphere.Sun", {{"elevation_deg", 30}, {"azimuth_deg", 160}}}}}}}}};
    load_scene(*world, doc, "bench");
    renderer = std::make_unique<Renderer>(*world);
    // Compile every shader variant and build the persistent LUTs before anything is timed.
    for (int i = 0; i < 3; ++i) renderer->render_frame({.index = frame++}, kW, kH);
  }

  // One frame: its finished wall time and its passes' times (serial on llvmpipe: each pass finished).
  double render(std::map<std::string, std::vector<double>>& passes) {
    FrameResult fr;
    world->resource<welkin::atmosphere::AtmosphereGpu>().forget_per_frame_luts();  // the cost of a moving view
    const double ms = finished_ms([&] { fr = renderer->render_frame({.index = frame++}, kW, kH); });
    double atmosphere = 0.0;
    for (const auto& t : fr.timings) {
      passes[t.name].push_back(t.gpu_ms);
      if (t.name.rfind("atmosphere.", 0) == 0) atmosphere += t.gpu_ms;
    }
    passes["atmosphere (all passes)"].push_back(atmosphere);
    passes["frame"].push_back(ms);
    return ms;
  }
};

double copy_floor_ms(Sky& sky) {
  return fullscreen_copy_floor_ms(sky.renderer->context().shaders, kW, kH, 31);
}

void report(benchmark::State& s, const std::map<std::string, std::vector<double>>& passes, double copy_ms,
            const std::string& prefix = "") {
  for (const auto& [name, ms] : passes) s.counters[prefix + name + "_ms"] = median(ms);
  s.counters["copy_ms"] = copy_ms;
  s.counters[prefix + "sky_x_copy"] = median(passes.at("atmosphere.sky")) / copy_ms;
  s.counters[prefix + "frame_x_copy"] = median(passes.at("frame")) / copy_ms;
}

void BM_Atmosphere_CopyFloor(benchmark::State& s) {
  Sky sky("lut", "low");  // any world: the copy uses the runtime's shaders
  for (auto _ : s)
    s.SetIterationTime(fullscreen_copy_floor_ms(sky.renderer->context().shaders, kW, kH, 1) * 1e-3);
}
BENCHMARK(BM_Atmosphere_CopyFloor)->UseManualTime()->Unit(benchmark::kMillisecond);

// One method and preset per benchmark: per-pass times and the sky pass against the copy.
void BM_Atmosphere_Frame(benchmark::State& s, const std::string& method, const std::string& quality) {
  Sky sky(method, quality);
  std::map<std::string, std::vector<double>> passes;
  for (auto _ : s) s.SetIterationTime(sky.render(passes) * 1e-3);
  report(s, passes, copy_floor_ms(sky));
}
BENCHMARK_CAPTURE(BM_Atmosphere_Frame, lut_low, "lut", "low")->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Atmosphere_Frame, lut_medium, "lut", "medium")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Atmosphere_Frame, lut_high, "lut", "high")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Atmosphere_Frame, lut_ultra, "lut", "ultra")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Atmosphere_Frame, raymarch_24x8, "raymarch", "high")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(8);

// The two ratios in one run, frames interleaved so that machine load hits both alike: the
// LUT path (at `quality`) against the nested raymarch (24 x 8), and the LUT path's sky pass against
// the copy.
void BM_Atmosphere_LutVsRaymarch(benchmark::State& s, const std::string& quality) {
  Sky lut("lut", quality), raymarch("raymarch", "high");
  std::map<std::string, std::vector<double>> lut_passes, raymarch_passes;
  for (auto _ : s) {
    const double ms = lut.render(lut_passes);
    raymarch.render(raymarch_passes);
    s.SetIterationTime(ms * 1e-3);
  }
  const double copy_ms = copy_floor_ms(lut);
  report(s, lut_passes, copy_ms, "lut_");
  s.counters["raymarch_frame_ms"] = median(raymarch_passes.at("frame"));
  s.counters["raymarch_atmosphere_ms"] = median(raymarch_passes.at("atmosphere (all passes)"));
  s.counters["speedup_frame"] = median(raymarch_passes.at("frame")) / median(lut_passes.at("frame"));
  s.counters["speedup_atmosphere"] = median(raymarch_passes.at("atmosphere (all passes)")) /
                                     median(lut_passes.at("atmosphere (all passes)"));
}
BENCHMARK_CAPTURE(BM_Atmosphere_LutVsRaymarch, lut_low, "low")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(15);
BENCHMARK_CAPTURE(BM_Atmosphere_LutVsRaymarch, lut_high, "high")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(15);

}  // namespace
