// welkin render SCENE [--out file.png|.exr] [--size WxH] [--frames N] [--timings] [--json] [--window]
//               [--metar REPORT]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "commands.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/scene_file.h"
#include "welkin/weather/components.h"

namespace welkin::cli {

namespace {

struct RenderOptions {
  std::string scene;
  std::string out;
  std::string size = "640x360";
  int frames = 1;
  double fps = 30.0;
  bool timings = false;
  bool json = false;
  bool window = false;
  std::vector<std::string> sets;
  std::string metar;
};

void print_timings(const std::vector<PassTiming>& avg, int frames) {
  std::fprintf(stdout, "%-36s %10s %10s   (mean over the %d frame%s each pass ran in)\n", "pass", "gpu ms", "cpu ms", frames, frames == 1 ? "" : "s");
  double g = 0, c = 0;
  for (const auto& t : avg) {
    std::fprintf(stdout, "%-36s %10.3f %10.3f\n", t.name.c_str(), t.gpu_ms, t.cpu_ms);
    g += t.gpu_ms;
    c += t.cpu_ms;
  }
  std::fprintf(stdout, "%-36s %10.3f %10.3f\n", "total", g, c);
}

// --metar: the scene's weather.Report (added when it has none) takes the report; the weather module
// sets the sky from it on the first update.
void set_metar(World& world, const std::string& report) {
  const ComponentInfo& info = world.modules().require_component(weather::Report::kTypeName);
  Registry& reg = world.registry();
  Entity target = reg.first<weather::Report>();
  if (target.is_null()) {
    target = reg.create();
    reg.emplace(target, *info.type);
  }
  try {
    resolve_field(*info.type, reg.get(target, info.type->id), "metar").set_json(report);
  } catch (const Error& e) {
    throw Error(ErrorInfo{
        .path = "--metar", .expected = e.info().expected, .found = e.info().found, .message = e.info().message});
  }
}

int run_render(const RenderOptions& o) {
  int w = 0, h = 0;
  parse_size(o.size, w, h);
  std::string out = o.out;
  if (out.empty()) out = "out/" + std::filesystem::path(o.scene).stem().string() + ".png";
  std::string ext = std::filesystem::path(out).extension().string();
  if (ext != ".png" && ext != ".exr")
    throw Error(ErrorInfo{.path = "--out", .expected = "a .png or .exr file name", .found = "'" + out + "'"});

  // Declared before the world: GL objects the world owns must die while their context lives.
  std::unique_ptr<GlContext> headless;
  std::unique_ptr<WindowContext> window;
  auto world = make_world();
  load_scene_file(*world, o.scene);  // before any GL work: bad input fails fast
  if (!o.metar.empty()) set_metar(*world, o.metar);
  for (const auto& s : o.sets) apply_assignment(*world, s);

  bool windowed = o.window && display_available();
  if (o.window && !windowed) std::fprintf(stderr, "welkin: no display found; rendering headless instead\n");
  if (windowed) window = std::make_unique<WindowContext>(w, h, "Welkin - " + o.scene);
  else headless = create_headless_context();

  Renderer renderer(*world);
  // Passes can differ between frames (LUTs rebuilt only on change), so timings average by name.
  std::vector<PassTiming> sum;
  std::vector<int> counts;
  FrameResult last;
  int frames = std::max(1, o.frames);
  auto start = std::chrono::steady_clock::now();
  for (int i = 0; windowed ? !window->should_close() : i < frames; ++i) {
    FrameInfo fi{.time_s = i / o.fps, .dt_s = i == 0 ? 0.0 : 1.0 / o.fps, .index = uint64_t(i)};
    if (windowed) window->framebuffer_size(w, h);
    last = renderer.render_frame(fi, std::max(w, 1), std::max(h, 1));
    for (const PassTiming& t : last.timings) {
      auto it = std::find_if(sum.begin(), sum.end(), [&](const PassTiming& s) { return s.name == t.name; });
      if (it == sum.end()) {
        sum.push_back(t);
        counts.push_back(1);
      } else {
        it->gpu_ms += t.gpu_ms;
        it->cpu_ms += t.cpu_ms;
        ++counts[size_t(it - sum.begin())];
      }
    }
    if (windowed) {
      GLuint fbo = 0;
      glCreateFramebuffers(1, &fbo);
      glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, renderer.output_texture().id(), 0);
      glBlitNamedFramebuffer(fbo, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      glDeleteFramebuffers(1, &fbo);
      window->swap_and_poll();
    } else if (frames > 1) {
      std::fprintf(stderr, "\rrendering frame %d/%d", i + 1, frames);
      if (i + 1 == frames) std::fprintf(stderr, "\n");
    }
    if (windowed) frames = i + 1;
  }
  double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (size_t k = 0; k < sum.size(); ++k) sum[k].gpu_ms /= counts[k], sum[k].cpu_ms /= counts[k];

  std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  if (ext == ".exr") write_exr(out, renderer.read_hdr());
  else write_png(out, renderer.read_output());

  if (o.json) {
    nlohmann::json j{{"output", out}, {"width", w}, {"height", h}, {"frames", frames}, {"wall_ms", wall}};
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& t : sum) passes.push_back({{"name", t.name}, {"gpu_ms", t.gpu_ms}, {"cpu_ms", t.cpu_ms}});
    j["passes"] = passes;
    j["culled_passes"] = last.culled_passes;
    j["modules"] = world->modules().loaded();
    j["systems"] = last.systems_run;
    std::fprintf(stdout, "%s\n", j.dump(2).c_str());
  } else {
    if (o.timings) print_timings(sum, frames);
    std::fprintf(stdout, "wrote %s (%dx%d)\n", out.c_str(), w, h);
  }
  return kOk;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to an image (headless unless --window and a display)");
  cmd->add_option("scene", opts->scene, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", opts->out, "Output .png (tone-mapped sRGB) or .exr (linear HDR); default out/<scene>.png");
  cmd->add_option("-s,--size", opts->size, "Image size WxH")->capture_default_str();
  cmd->add_option("-n,--frames", opts->frames, "Frames to render (timings are averaged)")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--fps", opts->fps, "Simulated frames per second")->check(CLI::Range(0.001, 1000.0))->capture_default_str();
  cmd->add_flag("-t,--timings", opts->timings, "Print GPU and CPU time per render pass");
  cmd->add_flag("--json", opts->json, "Print a machine-readable summary");
  cmd->add_flag("-w,--window", opts->window, "Show the frames in a window when a display is available");
  cmd->add_option("--set", opts->sets, "Override a field: component/path=value (repeatable)")->allow_extra_args(false)->take_all();
  cmd->add_option("--metar", opts->metar,
                  "Set the sky from a METAR report (weather.Report/metar; see `welkin metar`)");
  cmd->callback([opts, &exit_code] { exit_code = run_render(*opts); });
}

}  // namespace welkin::cli
