// The smallest complete host (docs/embedding.md): its window and ground, Welkin's sky. host-minimal SCENE
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <glm/gtc/matrix_transform.hpp>

#include "welkin/core/world.h"
#include "welkin/host/sky.h"
#include "welkin/scene/scene_file.h"

// A 20 km ground 2 m below the camera, which stays at the origin (so positions are camera-relative).
const char* kVertex =
    "#version 450 core\nuniform mat4 u_view_projection;\nout vec3 v_p;\n"
    "void main() { v_p = vec3(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2e4 - 1e4, -2.0);\n"
    "  gl_Position = u_view_projection * vec4(v_p, 1.0); }\n";
const char* kFragment =  // after Welkin's material functions: shade_lambert lights it as Welkin would
    "in vec3 v_p;\nout vec4 o;\n"
    "void main() { o = vec4(shade_lambert(vec3(0.2), vec3(0, 0, 1), v_p), 1.0); }\n";

int main(int argc, char** argv) {
  const int w = 960, h = 540;
  glfwInit();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWwindow* window = glfwCreateWindow(w, h, "Welkin inside a host", nullptr, nullptr);
  glfwMakeContextCurrent(window);
  welkin::World world;
  world.modules().add_search_dir(WELKIN_MODULE_DIR);
  welkin::load_scene_file(world, argc > 1 ? argv[1] : "scene.json");  // atmosphere, clock, clouds...
  welkin::host::Sky sky(world);
  const welkin::Program ground = sky.material_program(kVertex, kFragment);
  auto texture = [&](GLenum format, GLuint t = 0) {
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    return t;
  };
  const GLuint color = texture(GL_RGBA16F), depth = texture(GL_DEPTH_COMPONENT32F);
  const GLuint output = texture(GL_RGBA8);  // Welkin's exposed, tone-mapped sRGB frame
  GLuint vao = 0, fb = 0, out_fb = 0;
  glCreateVertexArrays(1, &vao);
  glCreateFramebuffers(1, &fb);
  glCreateFramebuffers(1, &out_fb);
  glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depth, 0);
  glNamedFramebufferTexture(out_fb, GL_COLOR_ATTACHMENT0, output, 0);
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.08), glm::dvec3(0.0, 0.0, 1.0));
  const glm::mat4 projection = glm::perspective(1.0f, float(w) / h, 0.5f, 30000.0f);  // forward depth
  const welkin::host::View host_view{view, projection, welkin::host::DepthConvention::forward};
  const welkin::host::Targets targets{
      .color = color, .depth = depth, .output = output, .width = w, .height = h};
  for (uint64_t i = 0; !glfwWindowShouldClose(window); ++i) {
    const welkin::host::Frame frame{
        .view = host_view, .targets = targets, .time_s = glfwGetTime(), .dt_s = 1 / 60.0, .index = i};
    sky.render(frame, [&] {  // the host's geometry, once this frame's lights are bound for its materials
      glBindFramebuffer(GL_FRAMEBUFFER, fb);
      glEnable(GL_DEPTH_TEST);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      ground.use();
      ground.set("u_view_projection", projection * glm::mat4(view));
      glBindVertexArray(vao);
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    });
    glBlitNamedFramebuffer(out_fb, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glfwSwapBuffers(window);
    glfwPollEvents();
  }
}
