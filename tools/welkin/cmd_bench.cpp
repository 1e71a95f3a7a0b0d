// welkin bench SCENE [--size WxH] [--frames N] [--form measured|fragment|compute] [--json]
// Frame and per-pass cost of a scene, as ratios against a full-screen copy of the same size measured
// in the same run (absolute times on shared machines are noise; ratios are what carry over), and the
// cost of each system (each path: the volumetric clouds, the mesh clusters, the god rays...).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "session.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/screen_pass.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

struct BenchOptions {
  std::string scene, size = "640x360";
  int frames = 30;
  double turn_deg = 0.0;  // the camera turns by this much each frame (nothing the view sees holds still)
  bool json = false;
  std::vector<std::string> sets;
  // The full-screen passes' form: the one measured for the device at start-up, or one forced (to time
  // both forms on one machine).
  std::string form = "measured";
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

int run_bench(const BenchOptions& o) {
  int w = 0, h = 0;
  parse_size(o.size, w, h);
  std::unique_ptr<GlContext> gl;
  auto world = make_world();
  load_scene_file(*world, o.scene);
  for (const auto& s : o.sets) apply_assignment(*world, s);
  gl = create_headless_context();
  Renderer renderer(*world);
  if (o.form != "measured") renderer.context().forms.forced["*"] = o.form == "compute" ? PassForm::compute : PassForm::fragment;
  for (int i = 0; i < 3; ++i) renderer.render_frame({.index = uint64_t(i)}, w, h);  // compile, allocate, fill LUTs
  // The copy is timed after every frame and each frame is divided by its own copy: the ratios then
  // hold while the machine's speed drifts during the run.
  CopyFloor copy(renderer.context().shaders, w, h);
  std::vector<double> frame_ms, copy_ms, frame_ratio, cpu_ms;
  std::vector<std::string> order, system_order;
  std::map<std::string, std::vector<double>> pass_ms, pass_ratio;
  // Each path (volumetric clouds, mesh clusters, god rays, ...) is a system: the sum of its passes per frame.
  std::map<std::string, std::vector<double>> system_ms, system_ratio;
  // A moving view rendered smaller (core.Camera/moving_render_scale): its size, and the last one's
  // output against the same view rendered whole and settled (16 still frames: temporal upscaling's
  // history then holds no pixel of the smaller frames), after the timed frames.
  int rendered_width = w, rendered_height = h;
  std::optional<ImageDifference> moving_error;
  double stopping_ms = 0.0;  // that next, still frame: the size changes back
  for (int i = 0; i < o.frames; ++i) {
    FrameResult fr;
    frame_ms.push_back(finished_ms([&] { fr = renderer.render_frame({.time_s = i / 30.0, .dt_s = 1 / 30.0, .index = uint64_t(i + 3)}, w, h); }));
    cpu_ms.push_back(fr.cpu_ms);
    copy_ms.push_back(copy.measure_ms(5));
    frame_ratio.push_back(frame_ms.back() / copy_ms.back());
    std::map<std::string, double> by_system;
    for (const auto& t : fr.timings) {
      if (!pass_ms.count(t.name)) order.push_back(t.name);
      pass_ms[t.name].push_back(t.gpu_ms);
      pass_ratio[t.name].push_back(t.gpu_ms / copy_ms.back());
      const std::string system = t.system.empty() ? "(renderer)" : t.system;
      if (!system_ms.count(system) && !by_system.count(system)) system_order.push_back(system);
      by_system[system] += t.gpu_ms;
    }
    for (const auto& [system, ms] : by_system) {
      system_ms[system].push_back(ms);
      system_ratio[system].push_back(ms / copy_ms.back());
    }
    if (fr.rendered_width != w || fr.rendered_height != h) rendered_width = fr.rendered_width, rendered_height = fr.rendered_height;
    if (i + 1 == o.frames && (fr.rendered_width != w || fr.rendered_height != h)) {
      const ImageU8 moving = renderer.read_output();
      stopping_ms = finished_ms([&] { renderer.render_frame({.time_s = i / 30.0, .dt_s = 0.0, .index = uint64_t(i + 4)}, w, h); });
      for (int k = 0; k < 16; ++k) renderer.render_frame({.time_s = i / 30.0, .dt_s = 0.0, .index = uint64_t(i + 5 + k)}, w, h);
      moving_error = image_difference(moving, renderer.read_output());
    }
    if (o.turn_deg != 0.0) {
      Registry& reg = world->registry();
      if (Camera* c = reg.get<Camera>(reg.first<Camera>())) c->heading_deg = float(std::fmod(c->heading_deg + o.turn_deg, 360.0));
    }
    std::fprintf(stderr, "\rbench frame %d/%d", i + 1, o.frames);
  }
  std::fprintf(stderr, "\n");
  const double floor = median(copy_ms), frame = median(frame_ms), ratio = median(frame_ratio);
  GlInfo info = gl->info();
  const PassFormProbe& probe = device_pass_form(renderer.context().shaders);
  const char* form = pass_form_name(renderer.context().forms.of("*"));
  if (o.json) {
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& n : order) {
      passes.push_back({{"name", n}, {"median_ms", median(pass_ms[n])}, {"ratio_to_copy", median(pass_ratio[n])},
                        {"frames", pass_ms[n].size()}});
    }
    nlohmann::json j{{"scene", o.scene}, {"width", w}, {"height", h}, {"frames", o.frames}, {"renderer", info.renderer},
                     {"copy_floor_ms", floor}, {"frame_median_ms", frame}, {"frame_ratio_to_copy", ratio},
                     {"cpu_frame_median_ms", median(cpu_ms)},
                     {"serial_pass_timing", renderer.context().backend.serial_timing()}, {"passes", passes}};
    j["pass_form"] = {{"used", form}, {"measured", pass_form_name(probe.chosen)},
                      {"probe_fragment_ms", probe.fragment_ms}, {"probe_compute_ms", probe.compute_ms},
                      {"probe_width", probe.width}, {"probe_height", probe.height}};
    nlohmann::json systems = nlohmann::json::array();
    for (const auto& n : system_order)
      systems.push_back({{"name", n}, {"median_ms", median(system_ms[n])}, {"ratio_to_copy", median(system_ratio[n])},
                         {"frames", system_ms[n].size()}});
    j["systems"] = systems;
    j["moving_rendered_width"] = rendered_width, j["moving_rendered_height"] = rendered_height;
    if (moving_error)
      j["moving_against_whole"] = {{"psnr_db", moving_error->psnr_db}, {"mean_steps", moving_error->mean}, {"max_steps", moving_error->max},
                                   {"stopping_frame_ms", stopping_ms}};
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf("%s at %dx%d, %d frames, %s\n", o.scene.c_str(), w, h, o.frames, info.renderer.c_str());
  std::printf("%-30s %10s %10s\n", "pass", "median ms", "x copy");
  for (const auto& n : order) std::printf("%-30s %10.3f %10.2f\n", n.c_str(), median(pass_ms[n]), median(pass_ratio[n]));
  std::printf("%-30s %10.3f %10.2f\n", "frame (finished)", frame, ratio);
  std::printf("%-30s %10.3f %10.2f\n", "full-screen copy (floor)", floor, 1.0);
  std::printf("%-30s %10.3f\n", "CPU per frame (not waiting)", median(cpu_ms));
  std::printf("full-screen passes: %s form (measured for this device: %s; tone map %.3f ms as fragment, %.3f ms as compute at %dx%d)\n",
              form, pass_form_name(probe.chosen), probe.fragment_ms, probe.compute_ms, probe.width, probe.height);
  if (rendered_width != w || rendered_height != h) {
    std::printf("moving frames rendered at %dx%d (core.Camera/moving_render_scale)", rendered_width, rendered_height);
    if (moving_error)
      std::printf("; the last against the same view rendered whole: PSNR %.1f dB, mean %.2f, max %d of 255"
                  " (that whole frame, the view stopped: %.1f ms)",
                  moving_error->psnr_db, moving_error->mean, moving_error->max, stopping_ms);
    std::printf("\n");
  }
  std::printf("\n%-30s %10s %10s\n", "system (its passes)", "median ms", "x copy");
  for (const auto& n : system_order) std::printf("%-30s %10.3f %10.2f\n", n.c_str(), median(system_ms[n]), median(system_ratio[n]));
  return kOk;
}

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Frame and per-pass cost of a scene as ratios to a full-screen copy");
  cmd->add_option("scene", o->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-s,--size", o->size, "Frame size WxH")->capture_default_str();
  cmd->add_option("-n,--frames", o->frames, "Measured frames (after 3 warm-up frames)")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--set", o->sets, "Override a field: component/path=value (repeatable)")->allow_extra_args(false)->take_all();
  cmd->add_option("--turn-deg", o->turn_deg, "Turn the camera by this many degrees each frame")->check(CLI::Range(-180.0, 180.0));
  cmd->add_option("--form", o->form, "Form of the full-screen passes: measured (per device, at start-up), fragment or compute")
      ->check(CLI::IsMember({"measured", "fragment", "compute"}))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Machine-readable output");
  cmd->callback([o, &exit_code] { exit_code = run_bench(*o); });
}

}  // namespace welkin::cli
