#pragma once
// The sky's colour of one pixel (sky.frag over a full-screen triangle, sky.comp over tiles): the sky
// behind everything (its depth test keeps it off the geometry). ATM_SKY_MODE 0: the
// sky-view LUT inside the atmosphere, one fetch; 1: a march through the LUTs from space (planet,
// limb and night side included); 2: method raymarch, a nested march per pixel. ATM_SKY_DISCS adds
// the sun and moon discs, on their small squares only (sky.vert), so most pixels never pay for them.
#include "atmosphere/raymarch.glsl"
#include "atmosphere/discs.glsl"
#ifndef ATM_SKY_MODE
#define ATM_SKY_MODE 0
#endif
#ifndef ATM_SKY_DISCS
#define ATM_SKY_DISCS 0
#endif
#ifndef ATM_SKY_GROUND_LIGHT
#define ATM_SKY_GROUND_LIGHT 0
#endif
// ATM_SKY_GROUND_ONLY (with the ground's light): only the rays that meet the ground are written, after
// the geometry (src/passes.cpp, ground_light_pass); the others keep what the sky pass drew.
#ifndef ATM_SKY_GROUND_ONLY
#define ATM_SKY_GROUND_ONLY 0
#endif
#if ATM_SKY_GROUND_LIGHT
#include "welkin/lighting.glsl"
#endif
uniform float u_pixel_angle;  // radians per pixel, for anti-aliased disc edges

// Luminance of the air (and the ground behind it) along unit direction v, in world axes.
vec3 sky_luminance(vec3 v) {
#if ATM_SKY_MODE == 0
  return atm_sky_view_lookup(v);
#elif ATM_SKY_MODE == 1
  return atm_march_ray(atm_camera(), v, 1e30, int(atm.raymarch_steps), false, true, atm_sun_light(),
                       atm_moon_light_source(), atm_ms_factor()).luminance;
#else
  return atm_raymarch(atm_camera(), v, int(atm.raymarch_steps), int(atm.raymarch_light_steps),
                      atm_sun_light(), atm_moon_light_source()).luminance;
#endif
}

#if ATM_SKY_GROUND_LIGHT
// The planet's ground is lit in the sky's luminance (the LUT or the march) by the whole sun, moon and
// sky. Where the light environment shadows a surface (cloud shadows, sky occlusion under a deck) or
// adds light to it, the ground gets the same as any material: what the shadows take is removed and
// what the terms add is added, through the transmittance from the camera to the ground.
bool meets_ground(vec3 iv) { return iv.z >= 0.5 && iv.y > iv.x; }
vec3 ground_light_change(vec3 v) {
  vec3 o = atm_camera();
  vec3 iv = atm_ray_interval(o, v, 1e30);
  if (!meets_ground(iv)) return vec3(0.0);
  vec3 g = o + v * iv.y;  // km, planet-centred
  vec3 n = normalize(g);
  vec3 p = v * (iv.y * 1000.0);  // camera-relative metres
  float r_c = length(o), r_g = atm_bottom() + atm.medium.lift_km;
  vec3 t_view =
      min(atm_transmittance(r_g, -dot(n, v)) / max(atm_transmittance(r_c, -dot(o / r_c, v)), vec3(1e-12)),
          vec3(1.0));
  AtmLight l0 = atm_sun_light(), l1 = atm_moon_light_source();
  float mu0 = dot(n, l0.direction);
  vec3 e_sun = l0.illuminance * atm_transmittance_to_light(r_g, mu0, l0.angular_radius) * max(mu0, 0.0);
  vec3 e_direct_taken = e_sun * (1.0 - welkin_light_visibility(p, n, 0));
#if ATM_MOON_LIGHT  // else the moon lights neither the sky nor surfaces
  float mu1 = dot(n, l1.direction);
  vec3 e_moon = l1.illuminance * atm_transmittance_to_light(r_g, mu1, l1.angular_radius) * max(mu1, 0.0);
  e_direct_taken += e_moon * (1.0 - welkin_light_visibility(p, n, 1));
#endif
  vec3 taken = atm.medium.ground_albedo / ATM_PI * e_direct_taken +
               atm_ms_factor() * atm_ground_sky_light(g, l0, l1) * (1.0 - welkin_sky_visibility(p, n));
  vec3 added = atm.medium.ground_albedo / ATM_PI * welkin_added_irradiance(p, n);
  return t_view * (added - taken);
}
#endif

// The sky's colour along v_dir (sky.vert: in the sky-view LUT's frame for the one-fetch case, else in
// world axes, not normalised), or false where the pixel keeps what it has (ATM_SKY_GROUND_ONLY: rays
// that miss the ground).
bool sky_pixel(vec3 v_dir, out vec4 color) {
#if ATM_SKY_MODE == 0 && !ATM_SKY_DISCS && !ATM_SKY_GROUND_LIGHT
  // The common case is one fetch: the LUT's values already fit RGBA16F.
  color = vec4(atm_sky_view_lookup_local(v_dir), 1.0);
#else
  vec3 v = normalize(v_dir);
#if ATM_SKY_GROUND_ONLY
  if (!meets_ground(atm_ray_interval(atm_camera(), v, 1e30))) return false;
#endif
  vec3 luminance = sky_luminance(v);
#if ATM_SKY_GROUND_LIGHT
  luminance = max(luminance + ground_light_change(v), vec3(0.0));
#endif
#if ATM_SKY_DISCS
  // Discs behind the air: transmittance from where the ray enters the atmosphere (or the camera).
  vec3 discs = atm_sun_disc(v, u_pixel_angle) + atm_moon_disc(v, u_pixel_angle);
  luminance += atm_transmittance_to_space(atm_camera(), v) * discs;
#endif
  color = vec4(atm_fit_half(luminance), 1.0);
#endif
  return true;
}
