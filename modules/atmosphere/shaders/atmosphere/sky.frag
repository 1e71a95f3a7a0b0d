// The sky behind everything (scene depth at infinity): the sky-view LUT inside the atmosphere, a
// march through the LUTs from space (planet, limb and night side included), then the discs.
#include "atmosphere/integrate.glsl"
#include "atmosphere/discs.glsl"
in vec2 v_ndc;
out vec4 o_color;
uniform sampler2D u_depth;
uniform float u_pixel_angle;  // radians per pixel, for anti-aliased disc edges

void main() {
  if (texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r > 0.0) discard;  // reversed Z: geometry here
  vec4 far_point = atm_inverse_view_projection * vec4(v_ndc, 0.5, 1.0);
  vec3 v = normalize(far_point.xyz / far_point.w);
  vec3 origin = atm_camera();
  vec3 luminance;
  if (atm_camera_in_space())
    luminance = atm_march_ray(origin, v, 1e30, int(atm_aerial_params.y), false, true, atm_sun_light(),
                              atm_moon_light_source(), false).luminance;
  else
    luminance = atm_sky_view_lookup(v);

  // Discs behind the air: transmittance from where the ray enters the atmosphere (or the camera).
  vec3 discs = atm_sun_disc(v, u_pixel_angle) + atm_moon_disc(v, u_pixel_angle);
  if (any(greaterThan(discs, vec3(0.0))) && !(atm_ray_sphere(origin, v, atm_bottom()).y > 0.0)) {
    vec3 t = vec3(1.0);
    vec2 top = atm_ray_sphere(origin, v, atm_top());
    if (top.y > 0.0) {
      vec3 p = origin + v * max(top.x, 0.0);
      float r = length(p);
      t = atm_transmittance(r, dot(p, v) / r);
    }
    luminance += t * discs;
  }
  o_color = vec4(atm_fit_half(luminance), 1.0);
}
