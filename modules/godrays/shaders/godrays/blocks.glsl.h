#pragma once
// The god rays' GPU block, declared once for GLSL (view_ray.glsl includes this file) and C++
// (src/frame_block.h includes it inside a namespace; welkin/gfx/gpu_block.h says how). Fields come in
// rows of 16 bytes (a vec4, four scalars, a vec3 and one scalar, or a mat4), so that std140 lays them
// out as C++ does; tests/modules/godrays/gpu_blocks_test.cpp reads every field back in a shader. No
// #include and no initialisers here.

// Per frame: the uniform block GodRaysFrame (src/shafts.cpp fills it), read by the shafts and their
// application.
struct GodRaysFrameGpu {
  mat4 inverse_view_projection;  // camera-relative
  vec3 up;                       // at the camera, from the planet's centre
  float max_distance_m;          // the shafts' rays: the air beyond is taken as lit
  float planet_radius_m;
  float camera_altitude_m;         // above the planet's radius
  float haze_density_per_m;        // the haze's density at the ground
  float haze_inverse_height_per_m;  // 1 / the haze's scale height
  float haze_scattering;           // per unit density
  float haze_absorption;
  float haze_g;  // Henyey-Greenstein asymmetry
  float reach;   // the screen-space shafts' taps: the fraction of the way to the sun's image they cover
  vec3 sun_direction;
  float jitter;  // this frame's offset of the per-pixel noise
  float sun_u;   // the sun's image (screen space, [0, 1])
  float sun_v;
  float unused_0;  // (padding)
  float unused_1;
};
