// A program of its own with Welkin inside: its GLFW window (or a headless EGL context), its camera,
// its geometry and shaders, its framebuffer. Each frame it draws, then hands Welkin its view,
// projection, colour and depth; Welkin adds the sky, clouds, god rays, haze and aerial perspective.
//
//   host-app SCENE [--size WxH] [--forward-depth] [--frames N --out DIR]
//
// Keys: WASD fly, Q/E down/up, arrows turn, shift faster, T/G the time of day later/earlier, Esc quits.
// With --frames N --out DIR it renders N frames headless and writes DIR/frame-NNNN.png.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "fly_camera.h"
#include "host_scene.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/host/sky.h"
#include "welkin/scene/scene_file.h"

namespace {

struct Options {
  std::string scene, out;
  int width = 960, height = 540, frames = 0;
  bool forward_depth = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return std::string(argv[++i]);
    };
    if (a == "--size") {
      if (std::sscanf(value().c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 1 || o.height < 1)
        throw std::runtime_error("--size takes WxH");
    } else if (a == "--frames")
      o.frames = std::stoi(value());
    else if (a == "--out")
      o.out = value();
    else if (a == "--forward-depth")
      o.forward_depth = true;
    else if (o.scene.empty() && a[0] != '-')
      o.scene = a;
    else
      throw std::runtime_error("unknown argument " + a);
  }
  if (o.scene.empty())
    throw std::runtime_error("usage: host-app SCENE [--size WxH] [--forward-depth] [--frames N --out DIR]");
  if ((o.frames > 0) != !o.out.empty()) throw std::runtime_error("--frames and --out go together");
  return o;
}

// The host's own camera starts where the scene's camera stands (the scene file is shared with
// `welkin render`); from then on it is the host's.
FlyCamera initial_camera(welkin::host::Sky& sky) {
  FlyCamera c;
  const nlohmann::json p = sky.get("core.Camera", "position_m");
  c.position = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
  c.heading_deg = sky.get("core.Camera", "heading_deg").get<double>();
  c.pitch_deg = sky.get("core.Camera", "pitch_deg").get<double>();
  c.vertical_fov_deg = sky.get("core.Camera", "vertical_fov_deg").get<double>();
  c.near_m = sky.get("core.Camera", "near_m").get<double>();
  return c;
}

void write_output(const HostTargets& t, const std::string& path) {
  welkin::ImageU8 img{t.width, t.height, std::vector<uint8_t>(size_t(t.width) * t.height * 4)};
  std::vector<uint8_t> rows(img.rgba.size());
  glGetTextureImage(t.output, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rows.size()), rows.data());
  const size_t row = size_t(t.width) * 4;
  for (int y = 0; y < t.height; ++y)  // GL's rows run bottom-up, an image's top-down
    std::memcpy(&img.rgba[size_t(y) * row], &rows[size_t(t.height - 1 - y) * row], row);
  welkin::write_png(path, img);
}

int run(const Options& o) {
  std::unique_ptr<welkin::GlContext> headless;
  GLFWwindow* window = nullptr;
  if (o.frames > 0) {
    headless = welkin::create_headless_context();
  } else {
    if (!glfwInit()) throw std::runtime_error("no display for a window (use --frames N --out DIR)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    window = glfwCreateWindow(o.width, o.height, "Welkin inside a host", nullptr, nullptr);
    if (!window) throw std::runtime_error("could not open an OpenGL 4.5 window");
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
  }
  {
    welkin::World world;
    world.modules().add_search_dir(WELKIN_MODULE_DIR);
    welkin::load_scene_file(world, o.scene);
    welkin::host::Sky sky(world);
    FlyCamera camera = initial_camera(sky);
    HostScene scene;
    scene.build_program(sky);
    uint64_t lighting = sky.lighting_version();
    std::unique_ptr<HostTargets> targets;
    double time_s = 0.0;
    for (uint64_t i = 0; window ? !glfwWindowShouldClose(window) : i < uint64_t(o.frames); ++i) {
      int w = o.width, h = o.height;
      double dt = 1.0 / 30.0;
      if (window) {
        glfwPollEvents();
        glfwGetFramebufferSize(window, &w, &h);
        const double now = glfwGetTime();
        dt = i == 0 ? 0.0 : now - time_s;
        time_s = now;
        camera.fly(window, dt);
        const double dh =
            (glfwGetKey(window, GLFW_KEY_T) == GLFW_PRESS) - (glfwGetKey(window, GLFW_KEY_G) == GLFW_PRESS);
        if (dh != 0.0) {  // an hour a second (a scene without a timeofday.TimeOfDay is an error here)
          const double hours = sky.get("timeofday.TimeOfDay", "local_time_h").get<double>() + dh * dt;
          sky.set("timeofday.TimeOfDay", "local_time_h", std::fmod(hours + 24.0, 24.0));
        }
        if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(window, 1);
        if (w < 1 || h < 1) continue;  // minimised
      } else {
        time_s = double(i) / 30.0, dt = i == 0 ? 0.0 : 1.0 / 30.0;  // `welkin render --frames`'s clock
      }
      if (!targets || targets->width != w || targets->height != h)
        targets = std::make_unique<HostTargets>(w, h);

      const bool reversed = !o.forward_depth;
      const glm::mat4 projection = camera.projection(double(w) / h, reversed);
      // Welkin calls it once this frame's sun, sky and shadows are bound for the host's materials
      // (recompiled first where the lighting changed: a module added, the moon set by day).
      auto draw = [&] {
        if (sky.lighting_version() != lighting) scene.build_program(sky), lighting = sky.lighting_version();
        scene.draw(*targets, projection * camera.rotation(), camera.position, reversed);
      };
      welkin::host::Frame frame;
      frame.view = {.view = camera.view(),
                    .projection = projection,
                    .depth = reversed ? welkin::host::DepthConvention::reversed
                                      : welkin::host::DepthConvention::forward};
      frame.targets = {.color = targets->color,
                       .depth = targets->depth,
                       .output = targets->output,
                       .width = w,
                       .height = h};
      frame.time_s = time_s, frame.dt_s = dt, frame.index = i;
      sky.render(frame, draw);

      if (window) {
        GLuint read = 0;
        glCreateFramebuffers(1, &read);
        glNamedFramebufferTexture(read, GL_COLOR_ATTACHMENT0, targets->output, 0);
        glBlitNamedFramebuffer(read, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glDeleteFramebuffers(1, &read);
        glfwSwapBuffers(window);
      } else {
        char name[32];
        std::snprintf(name, sizeof name, "frame-%04d.png", int(i));
        std::filesystem::create_directories(o.out);
        write_output(*targets, (std::filesystem::path(o.out) / name).string());
      }
    }
  }
  if (window) {
    glfwDestroyWindow(window);
    glfwTerminate();
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {  // welkin::Error names the file and the path inside it
    std::fprintf(stderr, "host-app: %s\n", e.what());
    return 1;
  }
}
