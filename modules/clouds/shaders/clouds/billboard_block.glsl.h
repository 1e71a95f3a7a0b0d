#pragma once
// One billboard, declared once for GLSL (clouds/billboards.glsl includes this file) and C++
// (src/billboards.h includes it inside a namespace; welkin/gfx/gpu_block.h says how). The placement
// compute (billboards_place.comp) writes it each frame, the billboards' draw reads it (std430). Fields
// come in rows of 16 bytes; tests/modules/clouds/gpu/gpu_blocks_test.cpp reads every field back in a
// shader. No #include and no initialisers here.
struct Billboard {
  vec3 centre;          // camera-relative m (the archetype box's centre)
  float depth_scale;    // the archetype's optical depth is scaled by it (0: no billboard)
  vec3 light;           // irradiance of the marched light at the centre
  float distance_m;     // of the centre from the camera
  vec3 sky;             // sky irradiance on a horizontal plane at the centre
  uint archetype;       // which archetype it shows
  vec3 ap_inscattering;  // the air between the camera and the centre
  float turn_rad;        // the archetype's turn about the vertical
  vec3 ap_transmittance;
  float transmittance_unused;  // (padding)
};
