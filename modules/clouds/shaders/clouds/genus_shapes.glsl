#pragma once
// The genera's own shapes (welkin/clouds/genera.h), included by density.glsl: cirrus's streaks along
// its wind and the cumulonimbus's anvil under its ceiling (mirrored by validation/cloud_field.cpp).

#ifndef CLOUDS_STREAKS
#define CLOUDS_STREAKS 1
#endif
#ifndef CLOUDS_ANVILS
#define CLOUDS_ANVILS 1
#endif

// Which of the genus's shapes (genera.h) the layer about to be evaluated has: 1 yes, 0 no, -1 decided
// from the layer's values at run time. The field's compiled layers set them as compile-time constants
// (CLOUDS_STREAK_MASK, CLOUDS_ANVIL_MASK), so that no other layer carries their code; a shader
// compiled without any (CLOUDS_STREAKS, CLOUDS_ANVILS 0) has none of it.
int clouds_layer_streaks = -1, clouds_layer_anvil = -1;

// A camera-relative offset v in a layer's stretched frame: `streak` times shorter along its wind (the
// noise read there varies that much more slowly along the wind; the identity for streak 1). Its
// noises' origins are in that frame (frame_block.cpp's `streaked`).
vec3 clouds_stretched(CloudLayerGpu L, vec3 v) {
#if CLOUDS_STREAKS
  return v - L.streak_axis * (dot(v, L.streak_axis) * (1.0 - 1.0 / L.streak));
#else
  return v;
#endif
}

// A camera-relative point x at height t in a layer, in the layer's streaked frame (genera.h): the base
// trails the top downwind by hook_m, curving away from the top (fall streaks, hooks), and the frame is
// stretched `streak` times along the wind (the noise varies that much more slowly along it: fibres).
// frame_block.cpp's `streaked` gives the noises' origins in it.
vec3 clouds_streaked(CloudLayerGpu L, vec3 x, float t) {
  return clouds_stretched(L, x + L.streak_axis * (L.hook_m * (1.0 - t) * (1.0 - t)));
}
float clouds_streaked_detail_fetch(CloudLayerGpu L, vec3 xs) {
  return textureLod(cl_detail_noise, L.streak_detail_origin + xs * cl.detail_per_m,
                    clouds_lod(1.0 / (cl.detail_per_m * 32.0)))
      .r;
}

// How far below the layer's threshold lo an anvil reaches at the most (clouds_anvil; 0 without one).
float clouds_anvil_reach(CloudLayerGpu L, float lo) {
  return max(1.0 - lo, L.filter_width) * (1.0 - sqrt(1.0 - L.anvil_start)) *
         max(L.anvil_spread - 1.0, 0.0);
}
// The anvil (cumulonimbus): from anvil_start up, the towers tall enough to reach it (those whose
// weather is strong enough that clouds_layer_top puts their top above anvil_start) spread out under
// the layer's ceiling (the tropopause): the weather's threshold falls from theirs, more with height (a
// flaring underside), to anvil_spread times lower at the top (1: the whole cloud's footprint; more:
// beyond it), and the top is flat. Returns its envelope at height t; a0 the weather's density there
// (both before the caller's clouds_weather_scale).
float clouds_anvil(CloudLayerGpu L, float w, float lo, float t, out float a0) {
  a0 = 0.0;
  float s = (t - L.anvil_start) / max(1.0 - L.anvil_start, 1e-3);
  if (s <= 0.0) return 0.0;
  float tall = max(1.0 - lo, L.filter_width) * (1.0 - sqrt(1.0 - L.anvil_start));
  float la = lo + tall * (1.0 - L.anvil_spread * smoothstep(0.0, 0.7, s));
  a0 = clamp((w - la) / L.filter_width, 0.0, 1.0);
  return a0 * smoothstep(0.0, 0.3, s) * (1.0 - smoothstep(0.88, 1.0, s));
}
