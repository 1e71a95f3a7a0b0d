#pragma once
// OpenGL 4.5 core contexts: headless through EGL (Mesa's surfaceless platform, llvmpipe on
// machines without a GPU) and windowed through GLFW. GL entry points come from libepoxy for both.
#include <memory>
#include <string>

struct GLFWwindow;

namespace welkin {

struct GlInfo {
  std::string vendor, renderer, version;
  // One line each: what results computed on this GL depend on (the disk cache's keys).
  std::string key() const { return vendor + "\n" + renderer + "\n" + version + "\n"; }
};
// The current context's implementation.
GlInfo current_gl_info();

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  GlInfo info() const;
};

// Creates a surfaceless OpenGL 4.5 core context; throws Error with the EGL failure otherwise.
std::unique_ptr<GlContext> create_headless_context();

class WindowContext : public GlContext {
 public:
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext() override;
  void make_current() override;
  bool should_close() const;
  void swap_and_poll();
  void framebuffer_size(int& w, int& h) const;
  GLFWwindow* handle() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

// True when a display server is reachable (GLFW can open a window).
bool display_available();

}  // namespace welkin
