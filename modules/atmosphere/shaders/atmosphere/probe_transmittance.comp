// `welkin probe`: transmittance along the camera's ray to the ground or the top of the atmosphere,
// by the functions a method renders with. ATM_SKY_MODE 0: the transmittance LUT (Bruneton's ratio
// of two lookups when the ray meets the ground); 2: method raymarch's own march along the ray.
#include "atmosphere/raymarch.glsl"
#ifndef ATM_SKY_MODE
#define ATM_SKY_MODE 0
#endif
layout(local_size_x = 1) in;
layout(rgba32f, binding = 0) uniform writeonly image2D o_transmittance;
uniform vec3 u_direction;

vec3 lut_transmittance(vec3 origin, vec3 dir) {
  vec3 iv = atm_ray_interval(origin, dir, 1e30);
  if (iv.y <= iv.x) return vec3(1.0);
  vec3 p = origin + dir * iv.x;
  float r = length(p), mu = dot(p, dir) / r;
  if (iv.z < 0.5) return atm_transmittance(r, mu);
  vec3 g = origin + dir * iv.y;
  float r_g = max(length(g), atm_bottom()), mu_g = dot(g, dir) / length(g);
  return min(atm_transmittance(r_g, -mu_g) / max(atm_transmittance(r, -mu), vec3(1e-30)), vec3(1.0));
}

void main() {
  vec3 dir = normalize(u_direction);
#if ATM_SKY_MODE == 2
  vec3 t = atm_raymarch(atm_camera(), dir, int(atm.raymarch_steps), int(atm.raymarch_light_steps),
                        atm_sun_light(), atm_moon_light_source()).transmittance;
#else
  vec3 t = lut_transmittance(atm_camera(), dir);
#endif
  imageStore(o_transmittance, ivec2(0), vec4(t, 1.0));
}
