#pragma once
// The clouds' shadow cascades as every material reads them: the uniform block CloudsShadow
// (clouds/light_term.glsl), declared once for GLSL and C++ (src/shadow_cascades.h includes this file
// inside a namespace; welkin/gfx/gpu_block.h says how), filled by src/shadow_cascades.cpp. Fields come
// in rows of 16 bytes; tests/modules/clouds/gpu/gpu_blocks_test.cpp reads every field back in a shader.
// No #include and no initialisers here.

// One cascade: a square plane across the sun's direction; a point p falls at
// uv = 0.5 + (dot(p - origin, axis_u), dot(p - origin, axis_v)) in its map.
struct CloudsShadowCascade {
  vec3 origin;   // camera-relative centre of the plane
  int valid;     // 1 while the cascade holds a map
  vec3 axis_u;   // the plane's axis per map unit
  float start_m;  // where the columns start, toward the sun from the plane
  vec3 axis_v;
  float side_m;  // the square's side
};

struct CloudsShadowGpu {
  CloudsShadowCascade cascades[4];  // nearest first (src/shadow_cascades.h: kMaxShadowCascades)
  vec3 light;                       // toward the sun
  float column_vertical;            // |sun.z|: the vertical fraction of a slanted column
  vec3 up;                          // up at the camera
  int cascade_count;                // 0: no shadows
  // The decks over the casters (layers that cast no shadow, all of them above every layer that
  // does: cirrus over cumulus): their optical depth toward the sun is in the map (CloudsShadowColumn), and
  // it dims the light of the clouds below this altitude (clouds_deck_light).
  float deck_base_m;                // the decks' lowest base
  float deck_top_m;                 // and highest top (base above top: none)
  float deck_unused_a;              // (padding)
  float deck_unused_b;              // (padding)
};
