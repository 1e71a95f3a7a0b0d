#pragma once
// The clouds' light term (src/light_term.cpp registers it): the sun's light through the cloud layers
// that cast shadows, from a shadow map (where the optical depth along each texel's column toward the
// sun crosses a few values: clouds/shadow_column.glsl), in cascades, and the sky occluded under them.
#include "clouds/shadow_block.glsl.h"
#include "clouds/shadow_column.glsl"
layout(std140, binding = WELKIN_BLOCK_CLOUDS_SHADOW) uniform CloudsShadow { CloudsShadowGpu cs; };
const int CLOUDS_SHADOW_CASCADES = 4;  // cs.cascades.length()
layout(binding = WELKIN_UNIT_CLOUDS_SHADOW_MAP) uniform sampler2D cs_map;  // the cascades side by side

// Where p falls in the shadow map: the nearest cascade that holds p (away from its edge, except in the
// last; none outside every cascade), p's place in that cascade's square, and `depth`, p's distance
// along the light from the cascade's start plane.
struct CloudsShadowPlace {
  int cascade;
  vec2 uv;
  bool found;
};
CloudsShadowPlace clouds_shadow_place(vec3 p, out float depth) {
  int n = cs.cascade_count;
  // The cascade is chosen first and read once (a software rasteriser would read every cascade a loop
  // passes, taken or not), by selects rather than branches. Materials ask for it once per point
  // (clouds_surface_light): asked by each of the three functions, it was computed three times.
  int chosen = -1;
  vec2 uv = vec2(0.0);
  for (int k = 0; k < CLOUDS_SHADOW_CASCADES; ++k) {
    vec3 q = p - cs.cascades[k].origin;
    vec2 c = vec2(0.5 + dot(q, cs.cascades[k].axis_u), 0.5 + dot(q, cs.cascades[k].axis_v));
    float margin = k + 1 < n ? 0.0625 : 0.0;
    bool inside = all(greaterThanEqual(c, vec2(margin))) && all(lessThanEqual(c, vec2(1.0 - margin)));
    bool take = chosen < 0 && k < n && inside;
    chosen = take ? k : chosen;
    uv = take ? c : uv;
  }
  const int k = max(chosen, 0);
  depth = cs.cascades[k].start_m - dot(p - cs.cascades[k].origin, cs.light);
  return CloudsShadowPlace(k, uv, chosen >= 0);
}

// The column at a place in a cascade's square, the cloud's body's (beam false) or the direct beam's
// through the eroded field (beam true: shadow_map.comp); none (no optical depth) where no cascade
// holds it.
CloudsShadowColumn clouds_shadow_read(CloudsShadowPlace at, bool beam) {
  // Kept half a texel inside the cascade's square: its neighbours in the texture are another cascade
  // and the other quarters of the column.
  float half_texel = 2.0 / float(textureSize(cs_map, 0).y);
  vec2 uv = clamp(at.uv, vec2(half_texel), vec2(1.0 - half_texel));
  float u = (float(at.cascade) + uv.x) / float(max(cs.cascade_count, 1));
  float v = 0.25 * uv.y + (beam ? 0.5 : 0.0);
  CloudsShadowColumn c = CloudsShadowColumn(texture(cs_map, vec2(u, v)), texture(cs_map, vec2(u, v + 0.25)));
  return at.found ? c : CloudsShadowColumn(vec4(0.0), vec4(0.0));
}

// The shadow map's column over p (the cloud's body) and p's depth along it.
CloudsShadowColumn clouds_shadow_column(vec3 p, out float depth) {
  return clouds_shadow_read(clouds_shadow_place(p, depth), false);
}

// The sunlight that reaches the cloud around p but not p: the direct beam's mean transmittance at p's
// depth over four columns `radius_m` from p's, across the light, less p's own (CloudsLightInputs.around;
// 0 where p's column is the lighter). Under a low sun a column through a broken field crosses several
// clouds while its neighbours toward the layer's top or beside it pass through the gaps; the light they
// let into the cloud diffuses to the sample. Both from the map alone, so that the layers that cast no
// shadow (haze, cirrus: in the light march's optical depth, not in the map's) do not read as a contrast.
float clouds_shadow_around(vec3 p, float radius_m) {
  float depth;
  CloudsShadowPlace at = clouds_shadow_place(p, depth);
  float step = radius_m / cs.cascades[at.cascade].side_m, sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    CloudsShadowPlace q = at;
    q.uv += vec2(i == 0 ? step : (i == 1 ? -step : 0.0), i == 2 ? step : (i == 3 ? -step : 0.0));
    sum += exp(-clouds_column_optical_depth(clouds_shadow_read(q, false), depth));
  }
  return max(0.25 * sum - exp(-clouds_column_optical_depth(clouds_shadow_read(at, false), depth)), 0.0);
}

// Optical depth of the clouds between p and the sun.
float clouds_shadow_optical_depth(vec3 p) {
  float depth;
  CloudsShadowColumn c = clouds_shadow_column(p, depth);
  return clouds_column_optical_depth(c, depth);
}

float clouds_light_visibility(vec3 p, vec3 n, int light) {
  if (light != 0) return 1.0;
  return exp(-clouds_shadow_optical_depth(p));
}

#include "clouds/transmittance.glsl"

float clouds_sky_visibility(vec3 p, vec3 n) {
  return clouds_diffuse_transmittance(clouds_shadow_optical_depth(p) * cs.column_vertical);
}

// The sunlight the deck scatters down rather than lets through directly (optical depth tau toward
// the sun), spread like an overcast sky (brighter overhead: the cosine-weighted irradiance of a
// uniform sky on a tilted plane). None without cloud: the two transmittances are then both 1.
vec3 clouds_scattered_down(vec3 sun_irradiance, float tau, vec3 n) {
  float diffuse = max(clouds_diffuse_transmittance(tau) - exp(-tau), 0.0);
  return sun_irradiance * (cs.column_vertical * diffuse * (0.5 + 0.5 * dot(n, cs.up)));
}

vec3 clouds_added_irradiance(vec3 p, vec3 n) {
  return clouds_scattered_down(welkin_sun_irradiance(p), clouds_shadow_optical_depth(p), n);
}

// The three at a surface point from one lookup of the shadow map.
void clouds_surface_light(vec3 p, vec3 n, inout WelkinSurfaceLight l) {
  float tau = clouds_shadow_optical_depth(p);
  l.sun_visibility *= exp(-tau);
  l.sky_visibility *= clouds_diffuse_transmittance(tau * cs.column_vertical);
  l.added_irradiance += clouds_scattered_down(l.sun_irradiance, tau, n);
}
