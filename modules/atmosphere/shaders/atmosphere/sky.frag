// The sky behind everything (its depth test keeps it off the geometry). ATM_SKY_MODE 0: the
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
in vec3 v_dir;
out vec4 o_color;
uniform float u_pixel_angle;  // radians per pixel, for anti-aliased disc edges

// Luminance of the air (and the ground behind it) along unit direction v, in world axes.
vec3 sky_luminance(vec3 v) {
#if ATM_SKY_MODE == 0
  return atm_sky_view_lookup(v);
#elif ATM_SKY_MODE == 1
  return atm_march_ray(atm_camera(), v, 1e30, int(atm_aerial_params.y), false, true, atm_sun_light(),
                       atm_moon_light_source(), atm_ms_factor()).luminance;
#else
  return atm_raymarch(atm_camera(), v, int(atm_aerial_params.y), int(atm_aerial_params.w), atm_sun_light(),
                      atm_moon_light_source()).luminance;
#endif
}

void main() {
#if ATM_SKY_MODE == 0 && !ATM_SKY_DISCS
  // The common case is one fetch: the LUT's values already fit RGBA16F.
  o_color = vec4(atm_sky_view_lookup_local(v_dir), 1.0);
#else
  vec3 v = normalize(v_dir);
  vec3 luminance = sky_luminance(v);
#if ATM_SKY_DISCS
  // Discs behind the air: transmittance from where the ray enters the atmosphere (or the camera).
  vec3 discs = atm_sun_disc(v, u_pixel_angle) + atm_moon_disc(v, u_pixel_angle);
  luminance += atm_transmittance_to_space(atm_camera(), v) * discs;
#endif
  o_color = vec4(atm_fit_half(luminance), 1.0);
#endif
}
