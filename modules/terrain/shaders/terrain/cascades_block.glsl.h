#pragma once
// The terrain's shadow cascades as every material reads them: the uniform block TerrainCascades
// (terrain/light_term.glsl), declared once for GLSL and C++ (src/terrain_gpu.h includes this file
// inside a namespace; welkin/gfx/gpu_block.h says how), filled by src/terrain_system.cpp. Fields come
// in rows of 16 bytes; tests/modules/terrain/gpu_blocks_test.cpp reads every field back in a shader.
// No #include and no initialisers here.

// One cascade: a square of the sun's view, nearest first.
struct TerrainCascade {
  mat4 light_view_projection;  // camera-relative world -> the cascade's clip space
  float far_m;                 // the view distance the cascade reaches
  float texel_m;               // its texel's size
  float unused_a;              // (padding)
  float unused_b;
};

struct TerrainCascadesGpu {
  TerrainCascade cascades[3];  // src/terrain_gpu.h: kShadowCascades
  int shadows_on;              // 1 while this frame made the cascades
  float unused_a;              // (padding)
  float unused_b;
  float unused_c;
};
