#pragma once
// The one ray-marching integrator behind every LUT and per-pixel march: in-scattered luminance of
// up to two lights (single scattering through the transmittance LUT, higher orders through the
// multi-scattering LUT), transmittance, and Hillaire's f_ms transfer for the multi-scattering LUT.
// Each step integrates its constant source analytically over the step's own extinction,
// S (1 - exp(-sigma_t dt)) / sigma_t (Hillaire 2015), so dense media neither gain energy nor NaN.
#include "atmosphere/common.glsl"

struct AtmLight {
  vec3 direction;    // towards the light
  vec3 illuminance;  // outside the atmosphere; zero disables the light
  float angular_radius;
};

struct AtmMarch {
  vec3 luminance;
  vec3 transmittance;
  vec3 ms_transfer;  // integral of T sigma_s: the fraction re-scattered (multi-scattering LUT only)
};

AtmMarch atm_march_start() { return AtmMarch(vec3(0.0), vec3(1.0), vec3(0.0)); }

// Light of `l` reaching radius r and scattered towards the camera: single scattering through the
// transmittance LUT and the planet's shadow, higher orders through the multi-scattering LUT.
vec3 atm_light_source(AtmLight l, vec3 up, float r, AtmMedium med, float rayleigh_phase, float mie_phase,
                      bool isotropic) {
  float mu = dot(up, l.direction);
  vec3 phase_scattering = med.rayleigh * rayleigh_phase + med.mie * mie_phase;
  vec3 s = atm_transmittance_to_light(r, mu, l.angular_radius) * phase_scattering;
  // The multi-scattering LUT must not be sampled while it is being written (isotropic pass).
  if (!isotropic) s += atm_absorption_extinction.w * atm_multiscattering(r, mu) * (med.rayleigh + med.mie);
  return l.illuminance * s;
}

// Accumulates [t0, t1] of the ray in `steps` midpoint steps, spaced uniformly or quadratically
// (dense near t0, where a camera inside the air sees most of its detail). `isotropic` replaces the
// phase functions by 1/(4 pi) and leaves out multi-scattering: the multi-scattering LUT's integrand.
void atm_march_segment(inout AtmMarch m, vec3 origin, vec3 dir, float t0, float t1, int steps, bool quadratic,
                       AtmLight l0, AtmLight l1, bool isotropic) {
  if (!(t1 > t0) || steps < 1) return;
  const float uniform_phase = 0.25 / ATM_PI;
  float c0 = dot(dir, l0.direction), c1 = dot(dir, l1.direction);
  float pr0 = isotropic ? uniform_phase : atm_rayleigh_phase(c0);
  float pm0 = isotropic ? uniform_phase : atm_mie_phase(c0);
  float pr1 = isotropic ? uniform_phase : atm_rayleigh_phase(c1);
  float pm1 = isotropic ? uniform_phase : atm_mie_phase(c1);
  bool use_l1 = any(greaterThan(l1.illuminance, vec3(0.0)));
  float n = float(steps);
  for (int i = 0; i < steps; ++i) {
    float a = float(i) / n, b = float(i + 1) / n;
    if (quadratic) a *= a, b *= b;
    float ta = mix(t0, t1, a), tb = mix(t0, t1, b);
    float dt = tb - ta;
    vec3 p = origin + dir * (0.5 * (ta + tb));
    float len = length(p);
    float r = max(len, atm_bottom() + atm_ground_albedo.w);
    vec3 up = p / max(len, 1e-20);
    AtmMedium med = atm_medium(r - atm_bottom());
    vec3 s = atm_light_source(l0, up, r, med, pr0, pm0, isotropic);
    if (use_l1) s += atm_light_source(l1, up, r, med, pr1, pm1, isotropic);
    vec3 x = med.extinction * dt;
    vec3 weight = dt * atm_one_minus_exp_over_x(x);  // integral of exp(-sigma_t t) over the step
    m.luminance += m.transmittance * s * weight;
    m.ms_transfer += m.transmittance * (med.rayleigh + med.mie) * weight;
    m.transmittance *= exp(-x);
  }
}

// Lambertian ground at planet-centred point p, lit directly by the lights (Hillaire 2020's ground).
vec3 atm_ground_luminance(vec3 p, AtmLight l0, AtmLight l1) {
  vec3 n = normalize(p);
  float r = atm_bottom() + atm_ground_albedo.w;
  float mu0 = dot(n, l0.direction), mu1 = dot(n, l1.direction);
  vec3 e = l0.illuminance * atm_transmittance_to_light(r, mu0, l0.angular_radius) * max(mu0, 0.0) +
           l1.illuminance * atm_transmittance_to_light(r, mu1, l1.angular_radius) * max(mu1, 0.0);
  return atm_ground_albedo.rgb / ATM_PI * e;
}

// The part of a ray inside the atmosphere: x = start, y = end (km), z = 1 when it ends on the ground.
// max_t clips it (a surface in front); returns y < x when the ray misses the air.
vec3 atm_ray_interval(vec3 origin, vec3 dir, float max_t) {
  vec2 top = atm_ray_sphere(origin, dir, atm_top());
  if (top.y <= 0.0) return vec3(0.0, -1.0, 0.0);
  float t0 = max(top.x, 0.0), t1 = top.y;
  vec2 ground = atm_ray_sphere(origin, dir, atm_bottom());
  float hit = 0.0;
  if (ground.y > 0.0) {
    float tg = ground.x > 0.0 ? ground.x : 0.0;
    if (tg < t1) t1 = tg, hit = 1.0;
  }
  if (max_t < t1) t1 = max_t, hit = 0.0;
  return vec3(t0, t1, hit);
}

// Integrates a whole ray (to max_t, the ground or the top), adding the lit ground when reached.
AtmMarch atm_march_ray(vec3 origin, vec3 dir, float max_t, int steps, bool quadratic, bool ground,
                       AtmLight l0, AtmLight l1, bool isotropic) {
  AtmMarch m = atm_march_start();
  vec3 iv = atm_ray_interval(origin, dir, max_t);
  if (iv.y <= iv.x) return m;
  atm_march_segment(m, origin, dir, iv.x, iv.y, steps, quadratic, l0, l1, isotropic);
  if (ground && iv.z > 0.5)
    m.luminance += m.transmittance * atm_ground_luminance(origin + dir * iv.y, l0, l1);
  return m;
}

// In-scattering and transmittance between the origin and a surface at distance t (km): the ground
// does not end it (the surface is in front of whatever the ideal sphere says), only the top does.
AtmMarch atm_march_to_surface(vec3 origin, vec3 dir, float t, int steps, AtmLight l0, AtmLight l1) {
  AtmMarch m = atm_march_start();
  vec2 top = atm_ray_sphere(origin, dir, atm_top());
  float t0 = max(top.x, 0.0), t1 = min(top.y, t);
  if (t1 > t0) atm_march_segment(m, origin, dir, t0, t1, steps, false, l0, l1, false);
  return m;
}

// The scene's lights from the uniform block (the moon only when it lights the sky).
AtmLight atm_sun_light() {
  return AtmLight(atm_sun_direction.xyz, atm_sun_illuminance.rgb, atm_sun_illuminance.w);
}
AtmLight atm_moon_light_source() {
  return AtmLight(atm_moon_direction.xyz, atm_flags.w > 0.5 ? atm_moon_illuminance.rgb : vec3(0.0),
                  atm_moon_illuminance.w);
}

// Camera position used by marches: moved up to the ground when under it.
vec3 atm_camera() { return atm_camera_km.xyz; }
