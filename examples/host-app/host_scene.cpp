#include "host_scene.h"

std::vector<HostObject> host_objects() {
  return {
      {{0.0, 0.0, -1.0}, {3000.0f, 3000.0f, 1.0f}, {0.22f, 0.24f, 0.16f}},  // the ground: its top at z = 0
      {{-30.0, 12.0, 3.0}, {3.0f, 3.0f, 3.0f}, {0.75f, 0.3f, 0.2f}},
      {{-45.0, -10.0, 6.0}, {4.0f, 4.0f, 6.0f}, {0.3f, 0.5f, 0.75f}},
      {{-150.0, 40.0, 15.0}, {8.0f, 8.0f, 15.0f}, {0.7f, 0.7f, 0.65f}},
      {{-1500.0, 300.0, 60.0},
       {150.0f, 150.0f, 60.0f},
       {0.5f, 0.45f, 0.4f}},  // a block 1.5 km out, in the haze
  };
}

namespace {

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 a_corner;  // a unit cube's corner
layout(location = 1) in vec3 a_normal;
uniform mat4 u_rotation_projection;
uniform vec3 u_center;  // camera-relative
uniform vec3 u_half_extent;
out vec3 v_position;
out vec3 v_normal;
void main() {
  v_position = u_center + a_corner * u_half_extent;
  v_normal = a_normal;
  gl_Position = u_rotation_projection * vec4(v_position, 1.0);
}
)";

const char* kFragmentMain = R"(in vec3 v_position;
in vec3 v_normal;
out vec4 o_color;
uniform vec3 u_albedo;
void main() { o_color = vec4(shade_lambert(u_albedo, normalize(v_normal), v_position), 1.0); }
)";

// A unit cube's 36 corners, counter-clockwise seen from outside, with the face normals.
std::vector<float> cube_vertices() {
  std::vector<float> v;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      auto corner = [&](int i, int j) {
        glm::vec3 c(0.0f), n(0.0f);
        c[axis] = float(sign), n[axis] = float(sign);
        c[u] = i ? 1.0f : -1.0f, c[w] = j ? 1.0f : -1.0f;
        v.insert(v.end(), {c.x, c.y, c.z, n.x, n.y, n.z});
      };
      const int quad[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
      for (int k = 0; k < 6; ++k) {
        const int at = sign > 0 ? k : 5 - k;  // the far side of the cube winds the other way
        corner(quad[at][0], quad[at][1]);
      }
    }
  return v;
}

}  // namespace

HostTargets::HostTargets(int w, int h) : width(w), height(h) {
  glCreateTextures(GL_TEXTURE_2D, 1, &color);
  glTextureStorage2D(color, 1, GL_RGBA16F, w, h);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth);
  glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
  glCreateTextures(GL_TEXTURE_2D, 1, &output);
  glTextureStorage2D(output, 1, GL_RGBA8, w, h);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
}

HostTargets::~HostTargets() {
  glDeleteFramebuffers(1, &framebuffer);
  const GLuint textures[] = {color, depth, output};
  glDeleteTextures(3, textures);
}

HostScene::HostScene() {
  const std::vector<float> v = cube_vertices();
  glCreateBuffers(1, &vertices_);
  glNamedBufferStorage(vertices_, GLsizeiptr(v.size() * sizeof(float)), v.data(), 0);
  glCreateVertexArrays(1, &vao_);
  glVertexArrayVertexBuffer(vao_, 0, vertices_, 0, 6 * sizeof(float));
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    glVertexArrayAttribBinding(vao_, a, 0);
  }
}

HostScene::~HostScene() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vertices_);
}

void HostScene::build_program(welkin::host::Sky& sky) {
  program_ = sky.material_program(kVertexShader, kFragmentMain);
}

void HostScene::draw(const HostTargets& t, const glm::mat4& rotation_projection, const glm::dvec3& camera_m,
                     bool reversed_depth) const {
  glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer);
  glViewport(0, 0, t.width, t.height);
  glClipControl(GL_LOWER_LEFT, reversed_depth ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(reversed_depth ? 0.0 : 1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(reversed_depth ? GL_GREATER : GL_LESS);
  glEnable(GL_CULL_FACE);
  program_.use();
  glBindVertexArray(vao_);
  program_.set("u_rotation_projection", rotation_projection);
  for (const HostObject& o : objects_) {
    const glm::vec3 center(o.center_m - camera_m);  // camera-relative in double, then float
    program_.set("u_center", center);
    program_.set("u_half_extent", o.half_extent_m);
    program_.set("u_albedo", o.albedo);
    glDrawArrays(GL_TRIANGLES, 0, 36);
  }
}
