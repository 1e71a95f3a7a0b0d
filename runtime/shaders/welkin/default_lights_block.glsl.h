#pragma once
// The runtime's default lights as their light term reads them: the uniform block WelkinDefaultLights
// (welkin/default_lights.glsl), declared once for GLSL and C++ (runtime/gfx/default_lights_block.h
// includes this file inside a namespace; welkin/gfx/gpu_block.h says how), filled by
// runtime/gfx/debug_content.cpp. Fields come in rows of 16 bytes; tests/runtime/gfx/gpu_blocks_test.cpp
// reads every field back in a shader. No #include and no initialisers here.
struct WelkinDefaultLightsGpu {
  vec3 direction;        // toward the light
  float sky_fraction;    // the sky's light as a fraction of the light's
  vec3 illuminance_lux;  // the light's, per colour channel
  float unused;          // (padding)
};
