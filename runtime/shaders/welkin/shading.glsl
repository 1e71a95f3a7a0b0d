#pragma once
// Surface shading shared by every material: Lambert and metallic-roughness PBR (GGX, Smith,
// Schlick) under the lights of welkin/lighting.glsl, which the runtime composes from the loaded
// modules' light terms (sources, their visibility, sky occlusion). Radiance out, in the lights' units.
#include "welkin/lighting.glsl"

const float WELKIN_PI = 3.14159265358979;

vec3 shade_lambert(vec3 albedo, vec3 normal, vec3 camera_relative_position) {
  vec3 p = camera_relative_position;
  WelkinSurfaceLight l = welkin_surface_light(p, normal);
  vec3 e = l.sun_irradiance * (max(dot(normal, welkin_sun_direction()), 0.0) * l.sun_visibility);
#if WELKIN_MOON_LIGHT
  e += welkin_moon_irradiance(p) * (max(dot(normal, welkin_moon_direction()), 0.0) * l.moon_visibility);
#endif
  e += welkin_sky_irradiance(normal) * l.sky_visibility + l.added_irradiance;
  return albedo / WELKIN_PI * e;
}

// One directional light on a metallic-roughness surface (Karis 2013: GGX, height-correlated Smith, Schlick).
vec3 pbr_direct(vec3 base_color, float metallic, float roughness, vec3 n, vec3 v, vec3 l, vec3 irradiance) {
  float n_dot_l = max(dot(n, l), 0.0);
  if (n_dot_l <= 0.0) return vec3(0.0);
  vec3 h = normalize(v + l);
  float n_dot_v = max(dot(n, v), 1e-4), n_dot_h = max(dot(n, h), 0.0), v_dot_h = max(dot(v, h), 0.0);
  float a = max(roughness * roughness, 1e-3), a2 = a * a;
  float d = a2 / (WELKIN_PI * pow(n_dot_h * n_dot_h * (a2 - 1.0) + 1.0, 2.0));
  float vis = 0.5 / (n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2) +
                     n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2));
  vec3 f0 = mix(vec3(0.04), base_color, metallic);
  vec3 f = f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
  vec3 diffuse = (1.0 - f) * (1.0 - metallic) * base_color / WELKIN_PI;
  return (diffuse + d * vis * f) * irradiance * n_dot_l;
}

// Sun, moon (where it reaches surfaces: WELKIN_MOON_LIGHT) and sky light on a PBR surface, each
// scaled by the light environment's visibility (shadow maps, cloud shadows, sky occlusion).
vec3 shade_pbr(vec3 base_color, float metallic, float roughness, float occlusion, vec3 n,
               vec3 camera_relative_position) {
  vec3 p = camera_relative_position;
  vec3 v = normalize(-p);
  WelkinSurfaceLight l = welkin_surface_light(p, n);
  vec3 c = pbr_direct(base_color, metallic, roughness, n, v, welkin_sun_direction(),
                      l.sun_irradiance * l.sun_visibility);
#if WELKIN_MOON_LIGHT
  c += pbr_direct(base_color, metallic, roughness, n, v, welkin_moon_direction(),
                  welkin_moon_irradiance(p) * l.moon_visibility);
#endif
  // Sky light: diffuse from the irradiance, specular approximated by the irradiance toward the reflection.
  vec3 f0 = mix(vec3(0.04), base_color, metallic);
  vec3 sky_diffuse = (welkin_sky_irradiance(n) * l.sky_visibility + l.added_irradiance) * (1.0 - metallic) *
                     base_color / WELKIN_PI;
  vec3 sky_specular = welkin_sky_irradiance(reflect(-v, n)) / WELKIN_PI * f0 * (1.0 - roughness * 0.7);
  return c + (sky_diffuse + sky_specular * l.sky_visibility) * occlusion;
}
