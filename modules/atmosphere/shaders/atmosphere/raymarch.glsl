#pragma once
// Method raymarch: the sky as it was rendered before LUTs (and as the seeds did), a march along
// every pixel's ray with, at each sample, a second march towards each light for its transmittance.
// Single scattering, the lit ground where the ray ends, and Hillaire's multiple-scattering term from
// the multi-scattering LUT, in the air and as sky light on that ground (scaled by the
// multiple-scattering factor, so 0 gives single scattering).
// It shares the medium, the phase functions and the per-step integral with the LUT path, so the two
// differ only in what the LUTs replace: the nested march and its step counts.
#include "atmosphere/integrate.glsl"

// Transmittance from radius r towards a light at zenith cosine mu to the top of the atmosphere, by
// `steps` midpoint samples; the planet's shadow as in atm_transmittance_to_light.
vec3 atm_light_march_transmittance(AtmParams P, float r, float mu, float angular_radius, int steps) {
  float visibility = atm_light_visibility(P, r, mu, angular_radius);
  float len = atm_distance_to_top(P, r, mu);
  float dt = len / float(steps);
  vec3 depth = vec3(0.0);
  for (int i = 0; i < steps; ++i) {
    float t = (float(i) + 0.5) * dt;
    float ri = sqrt(max(0.0, r * r + t * (t + 2.0 * r * mu)));
    depth += atm_medium(P, ri - P.bottom).extinction;
  }
  return exp(-depth * dt) * visibility;
}

vec3 atm_raymarch_light(AtmParams P, AtmLight l, vec3 up, float r, AtmMedium med, float rayleigh_phase,
                        float mie_phase, float mu_v, float nu, int light_steps) {
  float mu = dot(up, l.direction);
  vec3 t = atm_light_march_transmittance(P, r, mu, l.angular_radius, light_steps);
  vec3 s = t * (med.rayleigh * rayleigh_phase + med.mie * mie_phase);
  s += P.ms_factor * atm_multiscattering_source(P, r, mu, mu_v, nu, med);
  return l.illuminance * s;
}

// The whole ray from the origin to the ground or the top: `steps` uniform midpoint samples, each
// with `light_steps` towards every light.
AtmMarch atm_raymarch(vec3 origin, vec3 dir, int steps, int light_steps, AtmLight l0, AtmLight l1) {
  AtmMarch m = atm_march_start();
  vec3 iv = atm_ray_interval(origin, dir, 1e30);
  if (iv.y <= iv.x) return m;
  AtmParams P = atm_params();
  float c0 = dot(dir, l0.direction);
  float pr0 = atm_rayleigh_phase(c0), pm0 = atm_mie_phase(c0);
#if ATM_MOON_LIGHT
  float c1 = dot(dir, l1.direction);
  float pr1 = atm_rayleigh_phase(c1), pm1 = atm_mie_phase(c1);
#endif
  float dt = (iv.y - iv.x) / float(steps);
  for (int i = 0; i < steps; ++i) {
    vec3 p = origin + dir * (iv.x + (float(i) + 0.5) * dt);
    float len = length(p);
    float r = max(len, P.bottom + P.lift);
    vec3 up = p / max(len, 1e-20);
    AtmMedium med = atm_medium(P, r - P.bottom);
    float mu_v = dot(dir, up);
    vec3 s = atm_raymarch_light(P, l0, up, r, med, pr0, pm0, mu_v, c0, light_steps);
#if ATM_MOON_LIGHT
    if (atm_light_on(l1)) s += atm_raymarch_light(P, l1, up, r, med, pr1, pm1, mu_v, c1, light_steps);
#endif
    vec3 x = med.extinction * dt;
    m.luminance += m.transmittance * s * (dt * atm_one_minus_exp_over_x(x));
    m.transmittance *= exp(-x);
  }
  if (iv.z > 0.5) {
    vec3 g = origin + dir * iv.y;
    vec3 n = normalize(g);
    float r = P.bottom + P.lift;
    float mu0 = dot(n, l0.direction);
    vec3 e = l0.illuminance * atm_light_march_transmittance(P, r, mu0, l0.angular_radius, light_steps) *
             max(mu0, 0.0);
#if ATM_MOON_LIGHT
    float mu1 = dot(n, l1.direction);
    if (atm_light_on(l1))
      e += l1.illuminance * atm_light_march_transmittance(P, r, mu1, l1.angular_radius, light_steps) *
           max(mu1, 0.0);
#endif
    vec3 ground = atm.medium.ground_albedo / ATM_PI * e + P.ms_factor * atm_ground_sky_light(g, l0, l1);
    m.luminance += m.transmittance * ground;
  }
  return m;
}
