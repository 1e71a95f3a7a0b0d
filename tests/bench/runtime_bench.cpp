// Runtime benchmarks: ECS iteration against a plain array loop, render-graph compilation, and the
// frame's fixed passes against a full-screen copy of the same size (the floor), all in one run.
#include <benchmark/benchmark.h>

#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/shader.h"
#include "welkin/core/registry.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/renderer.h"

namespace {

using namespace welkin;

struct Pos {
  static constexpr std::string_view kTypeName = "bench.Pos";
  glm::vec3 v{0.0f};
};
void describe(TypeBuilder<Pos>& t) { t.field("v", &Pos::v); }
struct Vel {
  static constexpr std::string_view kTypeName = "bench.Vel";
  glm::vec3 v{1.0f};
};
void describe(TypeBuilder<Vel>& t) { t.field("v", &Vel::v); }

constexpr int kEntities = 100000;

void BM_Baseline_ArrayOfStructsLoop(benchmark::State& s) {
  struct Both {
    glm::vec3 p{0.0f}, v{1.0f};
  };
  std::vector<Both> items(kEntities);
  for (auto _ : s) {
    for (auto& b : items) b.p += b.v;
    benchmark::DoNotOptimize(items.data());
  }
  s.SetItemsProcessed(s.iterations() * kEntities);
}
BENCHMARK(BM_Baseline_ArrayOfStructsLoop);

void BM_Registry_EachTwoComponents(benchmark::State& s) {
  Registry r;
  for (int i = 0; i < kEntities; ++i) {
    Entity e = r.create();
    r.emplace<Pos>(e);
    if (i % int(s.range(0)) == 0) r.emplace<Vel>(e);
  }
  size_t n = 0;
  for (auto _ : s) {
    r.each<Pos, Vel>([&](Entity, Pos& p, Vel& v) { p.v += v.v; ++n; });
    benchmark::ClobberMemory();
  }
  s.SetItemsProcessed(int64_t(n));
}
BENCHMARK(BM_Registry_EachTwoComponents)->Arg(1)->Arg(10);

void BM_RenderGraph_Compile100Passes(benchmark::State& s) {
  Texture out;
  for (auto _ : s) {
    RenderGraph g;
    ResourceHandle target = g.import("out", out), prev;
    for (int i = 0; i < 100; ++i)
      g.add_pass("p" + std::to_string(i), [&](PassBuilder& b) {
        if (prev.valid()) b.read(prev);
        prev = i == 99 ? b.write(target) : b.create("t" + std::to_string(i), TextureDesc{.width = 64, .height = 64});
      }, [](PassContext&) {});
    g.present(target);
    benchmark::DoNotOptimize(g.compile());
    prev = {};
  }
}
BENCHMARK(BM_RenderGraph_Compile100Passes);

// GPU: 640x360, forced to completion every iteration.
constexpr int kW = 640, kH = 360;

GlContext& gl() {
  static std::unique_ptr<GlContext> ctx = create_headless_context();
  return *ctx;
}

void BM_Gpu_FullscreenCopy_Floor(benchmark::State& s) {
  gl();
  ShaderLibrary lib;
  lib.add_search_dir(runtime_shader_dir());
  for (auto _ : s) s.SetIterationTime(fullscreen_copy_floor_ms(lib, kW, kH, 1) * 1e-3);
}
BENCHMARK(BM_Gpu_FullscreenCopy_Floor)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_Gpu_DebugSceneFrame(benchmark::State& s) {
  gl();
  World world;
  auto& reg = world.registry();
  reg.emplace<Camera>(reg.create());
  reg.emplace<Backdrop>(reg.create());
  reg.emplace<DebugShape>(reg.create());
  Renderer r(world);
  r.render_frame({}, kW, kH);
  std::map<std::string, double> pass_ms;
  for (auto _ : s) {
    FrameResult fr;
    double ms = finished_ms([&] { fr = r.render_frame({}, kW, kH); });
    s.SetIterationTime(ms * 1e-3);
    for (const auto& t : fr.timings) pass_ms[t.name] += t.gpu_ms;
  }
  for (auto& [name, ms] : pass_ms) s.counters[name + "_ms"] = ms / double(s.iterations());
}
BENCHMARK(BM_Gpu_DebugSceneFrame)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
