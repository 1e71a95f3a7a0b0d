#include "welkin/gfx/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>

#include "welkin/core/error.h"

namespace welkin {

GlInfo current_gl_info() {
  auto str = [](GLenum e) {
    auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return GlInfo{str(GL_VENDOR), str(GL_RENDERER), str(GL_VERSION)};
}

GlInfo GlContext::info() const { return current_gl_info(); }

namespace {

class HeadlessContext : public GlContext {
 public:
  HeadlessContext() {
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
      throw Error(
          "headless GL: EGL_MESA_platform_surfaceless is not available (install Mesa's EGL: libegl-mesa0)");
    display_ = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr))
      throw Error("headless GL: cannot initialise the EGL surfaceless display");
    if (!eglBindAPI(EGL_OPENGL_API)) throw Error("headless GL: EGL cannot bind the OpenGL API");
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0)
      throw Error("headless GL: no EGL config supports desktop OpenGL");
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (context_ == EGL_NO_CONTEXT) throw Error("headless GL: cannot create an OpenGL 4.5 core context");
    make_current();
  }
  ~HeadlessContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void make_current() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw Error("headless GL: eglMakeCurrent failed");
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> create_headless_context() { return std::make_unique<HeadlessContext>(); }

bool display_available() {
  const char* d = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (d && *d) || (w && *w);
}

WindowContext::WindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) throw Error("window: GLFW cannot initialise (is a display available?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) throw Error("window: cannot create a window with an OpenGL 4.5 core context");
  make_current();
  glfwSwapInterval(1);
}

WindowContext::~WindowContext() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void WindowContext::make_current() { glfwMakeContextCurrent(window_); }
bool WindowContext::should_close() const { return glfwWindowShouldClose(window_); }
void WindowContext::swap_and_poll() {
  glfwSwapBuffers(window_);
  glfwPollEvents();
}
void WindowContext::framebuffer_size(int& w, int& h) const { glfwGetFramebufferSize(window_, &w, &h); }

}  // namespace welkin
