#pragma once
// The terrain's light term (src/terrain_system.cpp registers it): the sun's cascaded shadow maps,
// three cascades side by side in one compare atlas, for every material of the scene.
#include "terrain/cascades_block.glsl.h"
layout(std140, binding = WELKIN_BLOCK_TERRAIN_CASCADES) uniform TerrainCascades { TerrainCascadesGpu tc; };
layout(binding = WELKIN_UNIT_TERRAIN_SHADOW_ATLAS) uniform sampler2DShadow terrain_shadow_atlas;

// Fraction of the sun reaching a point: the nearest cascade that covers it, a 3x3 box of hardware-PCF
// taps (in four).
// The cascades are made for the sun only (the moon's light is left unshadowed by the terrain).
// Shaders that sample the light at many points per pixel define WELKIN_VOLUME_SAMPLES: one tap each.
float terrain_light_visibility(vec3 camera_relative, vec3 normal, int light) {
  if (light != 0 || tc.shadows_on == 0) return 1.0;
  float d = length(camera_relative);
  int c = d < tc.cascades[0].far_m ? 0 : d < tc.cascades[1].far_m ? 1 : d < tc.cascades[2].far_m ? 2 : 3;
  if (c == 3) return 1.0;
  // Normal offset of two texels: a grazing sun on gentle slopes otherwise shadows the surface itself.
  vec4 clip = tc.cascades[c].light_view_projection *
              vec4(camera_relative + normal * 2.0 * tc.cascades[c].texel_m, 1.0);
  vec3 p = clip.xyz / clip.w;
  vec2 uv = p.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
#ifdef WELKIN_VOLUME_SAMPLES
  // Many samples per pixel (shafts in the air): one hardware-filtered tap, their sum filters.
  return texture(terrain_shadow_atlas, vec3((float(c) + uv.x) / 3.0, uv.y, p.z));
#else
  // The 3x3 hardware taps at whole-texel offsets weigh the 4x4 texels around the point, per axis,
  // (1 - f, 1, 1, f) / 3 (f: the point's fraction between texel centres). Two hardware taps per axis
  // give those weights exactly, at a bilinear fraction 1 / (2 - f) between the first two texels and
  // f / (1 + f) between the last two: four taps instead of nine, the same filter.
  vec2 size = vec2(textureSize(terrain_shadow_atlas, 0));
  vec2 s = vec2((float(c) + uv.x) / 3.0, uv.y) * size - 0.5;
  vec2 i = floor(s), f = s - i;
  vec2 w0 = 2.0 - f, w1 = 1.0 + f;
  vec2 a = (i - 1.0 + 1.0 / w0 + 0.5) / size, b = (i + 1.0 + f / w1 + 0.5) / size;
  float lit = w0.x * w0.y * texture(terrain_shadow_atlas, vec3(a.x, a.y, p.z)) +
              w1.x * w0.y * texture(terrain_shadow_atlas, vec3(b.x, a.y, p.z)) +
              w0.x * w1.y * texture(terrain_shadow_atlas, vec3(a.x, b.y, p.z)) +
              w1.x * w1.y * texture(terrain_shadow_atlas, vec3(b.x, b.y, p.z));
  return lit / 9.0;
#endif
}
