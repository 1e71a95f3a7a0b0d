#include "fly_camera.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

glm::dvec3 FlyCamera::forward() const {
  const double h = glm::radians(heading_deg), p = glm::radians(pitch_deg);
  return {std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p)};
}

glm::dvec3 FlyCamera::right() const {
  const double h = glm::radians(heading_deg);
  return {std::cos(h), -std::sin(h), 0.0};
}

glm::dmat4 FlyCamera::view() const {
  const glm::dvec3 f = forward(), r = right(), u = glm::cross(r, f);
  glm::dmat4 v(1.0);
  for (int i = 0; i < 3; ++i) v[i] = glm::dvec4(r[i], u[i], -f[i], 0.0);  // rows: right, up, -forward
  v[3] = glm::dvec4(-glm::dot(r, position), -glm::dot(u, position), glm::dot(f, position), 1.0);
  return v;
}

glm::mat4 FlyCamera::rotation() const {
  glm::dmat4 v = view();
  v[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);
  return glm::mat4(v);
}

glm::mat4 FlyCamera::projection(double aspect, bool reversed_depth) const {
  const float fov = float(glm::radians(vertical_fov_deg));
  if (!reversed_depth) return glm::perspective(fov, float(aspect), float(near_m), float(far_m));
  const float f = 1.0f / std::tan(0.5f * fov);
  glm::mat4 p(0.0f);
  p[0][0] = f / float(aspect);
  p[1][1] = f;
  p[2][3] = -1.0f;
  p[3][2] = float(near_m);
  return p;
}

void FlyCamera::fly(GLFWwindow* w, double dt) {
  auto down = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0 : 0.0; };
  const double speed = 20.0 * (down(GLFW_KEY_LEFT_SHIFT) * 9.0 + 1.0) * dt;
  const glm::dvec3 f = forward(), ground_forward = glm::normalize(glm::dvec3(f.x, f.y, 0.0));
  position += speed * ((down(GLFW_KEY_W) - down(GLFW_KEY_S)) * ground_forward +
                       (down(GLFW_KEY_D) - down(GLFW_KEY_A)) * right() +
                       (down(GLFW_KEY_E) - down(GLFW_KEY_Q)) * glm::dvec3(0.0, 0.0, 1.0));
  const double turn = 60.0 * dt;
  heading_deg = std::fmod(heading_deg + turn * (down(GLFW_KEY_RIGHT) - down(GLFW_KEY_LEFT)) + 360.0, 360.0);
  pitch_deg = std::clamp(pitch_deg + turn * (down(GLFW_KEY_UP) - down(GLFW_KEY_DOWN)), -89.0, 89.0);
}
