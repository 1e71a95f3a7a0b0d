#pragma once
// Shader permutations the atmosphere's passes share (passes.cpp, frame_passes.cpp).
#include <glm/glm.hpp>

#include "welkin/atmosphere/gpu.h"
#include "welkin/gfx/shader.h"

namespace welkin::atmosphere {

// Shader permutations of one frame: software rasterisers run both sides of every branch, so
// features a frame does not use are compiled out rather than branched around.
inline bool moon_lights(const FrameBlock& u) {
  return u.moon_lights_sky > 0.5f && glm::any(glm::greaterThan(u.moon_illuminance, glm::vec3(0.0f)));
}

inline ShaderDefines moon_defines(const FrameBlock& u) {
  return {{"ATM_MOON_LIGHT", moon_lights(u) ? "1" : "0"}};
}

inline bool in_space(const FrameBlock& u) {
  return u.camera_in_space > 0.5f;
}

}  // namespace welkin::atmosphere
