#pragma once
// The host's own geometry, shaders and render targets: a flat ground and a few boxes, drawn
// camera-relative into a framebuffer of its own (linear radiance in RGBA16F, depth in 32-bit float).
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "welkin/host/sky.h"

struct HostObject {
  glm::dvec3 center_m;
  glm::vec3 half_extent_m;
  glm::vec3 albedo;
};
// tests/package/host_objects.json holds the same objects as core.DebugShape boxes, for `welkin render`.
std::vector<HostObject> host_objects();

struct HostTargets {
  int width = 0, height = 0;
  GLuint framebuffer = 0, color = 0, depth = 0, output = 0;
  HostTargets(int width, int height);
  ~HostTargets();
  HostTargets(const HostTargets&) = delete;
  HostTargets& operator=(const HostTargets&) = delete;
};

class HostScene {
 public:
  HostScene();
  ~HostScene();
  HostScene(const HostScene&) = delete;
  HostScene& operator=(const HostScene&) = delete;
  // The fragment shader lights its surfaces with Welkin's material functions (Sky::material_program);
  // the vertex shader is the host's alone. Again when Sky::lighting_version changes.
  void build_program(welkin::host::Sky& sky);
  // Clears and draws the objects; `rotation_projection` is projection x rotation-only view, the
  // objects are placed relative to `camera_m` in double precision.
  void draw(const HostTargets& targets, const glm::mat4& rotation_projection, const glm::dvec3& camera_m,
            bool reversed_depth) const;

 private:
  std::vector<HostObject> objects_ = host_objects();
  welkin::Program program_;
  GLuint vao_ = 0, vertices_ = 0;
};
