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

// The moon's light in the air is a permutation of the atmosphere's own passes (0 or 1): a second
// light doubles the cost of every step, and software rasterisers run masked-off branches anyway.
// Materials that include this without defining it test the light at run time.
#ifndef ATM_MOON_LIGHT
#define ATM_MOON_LIGHT 1
#define ATM_MOON_LIGHT_DYNAMIC 1
#endif
#ifdef ATM_MOON_LIGHT_DYNAMIC
bool atm_light_on(AtmLight l) { return any(greaterThan(l.illuminance, vec3(0.0))); }
#else
bool atm_light_on(AtmLight l) { return true; }
#endif

// What a march accumulates, and the sample at the end of its last segment, which the next segment of
// the same ray can start from (atm_march_segment_resume).
struct AtmSample {
  vec3 source;      // light scattered towards the camera per km, before the camera's transmittance
  vec3 extinction;  // 1/km
  vec3 scattering;  // 1/km
};

struct AtmMarch {
  vec3 luminance;
  vec3 transmittance;
  vec3 ms_transfer;  // integral of T sigma_s: the fraction re-scattered (multi-scattering LUT only)
  AtmSample end;
  float end_t;  // < 0: no sample yet
};

AtmMarch atm_march_start() {
  return AtmMarch(vec3(0.0), vec3(1.0), vec3(0.0), AtmSample(vec3(0.0), vec3(0.0), vec3(0.0)), -1.0);
}

// Mean over a step of a quantity that varies exponentially between its end values a and b (exact
// for an exponential, which the air's density and the sunlight through it nearly are): the
// midpoint rule underestimates such a step by h^2 / 24 scale heights^2, 1.7% of the Mie peak
// with Hillaire's 30 steps. Equal ends or a zero end (shadow, a profile's edge) take the arithmetic mean.
vec3 atm_log_mean(vec3 a, vec3 b) {
  vec3 lo = min(a, b), hi = max(a, b);
  vec3 ratio = hi / max(lo, vec3(1e-30));
  vec3 lm = (hi - lo) / log(max(ratio, vec3(1.0 + 1e-6)));
  bvec3 arithmetic = bvec3(vec3(lessThan(ratio, vec3(1.0 + 1e-3))) + vec3(lessThanEqual(lo, vec3(0.0))));
  return mix(lm, 0.5 * (a + b), arithmetic);
}

// Weight of the multi-scattering LUT's term in a march: the scene's multiple-scattering factor for
// what is seen; 0 and 1 while the LUT itself is built (multiscattering_lut.comp).
float atm_ms_factor() { return atm.medium.multiple_scattering_factor; }

// Light of `l` reaching radius r and scattered towards the camera: single scattering through the
// transmittance LUT and the planet's shadow, higher orders through the multi-scattering LUT.
vec3 atm_light_source(AtmParams P, AtmLight l, vec3 up, float r, AtmMedium med, float rayleigh_phase,
                      float mie_phase, float mu_v, float nu, float ms_weight) {
  float mu = dot(up, l.direction);
  vec3 phase_scattering = med.rayleigh * rayleigh_phase + med.mie * mie_phase;
  vec3 s = atm_transmittance_to_light(P, r, mu, l.angular_radius) * phase_scattering;
  // A branch, not a product: the LUT's first build must not read the texture it is writing.
  if (ms_weight > 0.0) s += ms_weight * atm_multiscattering_source(P, r, mu, mu_v, nu, med);
  return l.illuminance * s;
}

// Phase functions of one ray and its lights, and the sample of the medium and its light at a point.
struct AtmRayLights {
  vec3 dir;
  AtmLight l0, l1;
  float pr0, pm0, pr1, pm1;  // Rayleigh and Mie phase of each light for this ray
  float nu0, nu1;            // cosine between the ray and each light
  float ms_weight;
};

AtmRayLights atm_ray_lights(vec3 dir, AtmLight l0, AtmLight l1, float ms_weight) {
  float c0 = dot(dir, l0.direction), c1 = dot(dir, l1.direction);
  return AtmRayLights(dir, l0, l1, atm_rayleigh_phase(c0), atm_mie_phase(c0), atm_rayleigh_phase(c1),
                      atm_mie_phase(c1), c0, c1, ms_weight);
}

AtmSample atm_sample(AtmParams P, AtmRayLights L, vec3 p) {
  float len = length(p);
  float r = max(len, P.bottom + P.lift);
  vec3 up = p / max(len, 1e-20);
  AtmMedium med = atm_medium(P, r - P.bottom);
  float mu_v = dot(L.dir, up);
  vec3 s = atm_light_source(P, L.l0, up, r, med, L.pr0, L.pm0, mu_v, L.nu0, L.ms_weight);
#if ATM_MOON_LIGHT
  if (atm_light_on(L.l1)) s += atm_light_source(P, L.l1, up, r, med, L.pr1, L.pm1, mu_v, L.nu1, L.ms_weight);
#endif
  return AtmSample(s, med.extinction, med.rayleigh + med.mie);
}

// Accumulates [t0, t1] of the ray in `steps` steps from the sample `a` at t0, spaced uniformly or
// quadratically (dense near t0, where a camera inside the air sees most of its detail). The medium
// and its light are sampled at the step ends and averaged as exponentials (atm_log_mean); within a
// step the source is integrated against the step's own extinction, S (1 - exp(-sigma_t dt)) / sigma_t.
void atm_march_steps(inout AtmMarch m, AtmParams P, AtmRayLights L, AtmSample a, vec3 origin, vec3 dir,
                     float t0, float t1, int steps, bool quadratic) {
  float n = float(steps), ta = t0;
  for (int i = 0; i < steps; ++i) {
    float f = float(i + 1) / n;
    if (quadratic) f *= f;
    float tb = mix(t0, t1, f);
    float dt = tb - ta;
    AtmSample b = atm_sample(P, L, origin + dir * tb);
    vec3 x = atm_log_mean(a.extinction, b.extinction) * dt;
    vec3 weight = dt * atm_one_minus_exp_over_x(x);  // integral of exp(-sigma_t t) over the step
    m.luminance += m.transmittance * atm_log_mean(a.source, b.source) * weight;
    m.ms_transfer += m.transmittance * atm_log_mean(a.scattering, b.scattering) * weight;
    m.transmittance *= exp(-x);
    a = b;
    ta = tb;
  }
  m.end = a;
  m.end_t = t1;
}

void atm_march_segment(inout AtmMarch m, vec3 origin, vec3 dir, float t0, float t1, int steps, bool quadratic,
                       AtmLight l0, AtmLight l1, float ms_weight) {
  if (!(t1 > t0) || steps < 1) return;
  AtmParams P = atm_params();
  AtmRayLights L = atm_ray_lights(dir, l0, l1, ms_weight);
  atm_march_steps(m, P, L, atm_sample(P, L, origin + dir * t0), origin, dir, t0, t1, steps, quadratic);
}

// The next segment [end of the last one, t1] of the same ray, from the sample the last one ended
// with (aerial-perspective slices), so that a step costs one sample. A separate function rather than
// a test: software rasterisers would take the sample anyway.
void atm_march_segment_resume(inout AtmMarch m, vec3 origin, vec3 dir, float t1, int steps, AtmLight l0,
                              AtmLight l1, float ms_weight) {
  if (!(t1 > m.end_t) || steps < 1) return;
  AtmParams P = atm_params();
  AtmRayLights L = atm_ray_lights(dir, l0, l1, ms_weight);
  atm_march_steps(m, P, L, m.end, origin, dir, m.end_t, t1, steps, false);
}

// Lambertian ground at planet-centred point p, lit directly by the lights (Hillaire 2020's ground).
vec3 atm_ground_luminance(vec3 p, AtmLight l0, AtmLight l1) {
  vec3 n = normalize(p);
  float r = atm_bottom() + atm.medium.lift_km;
  float mu0 = dot(n, l0.direction);
  vec3 e = l0.illuminance * atm_transmittance_to_light(r, mu0, l0.angular_radius) * max(mu0, 0.0);
#if ATM_MOON_LIGHT
  float mu1 = dot(n, l1.direction);
  e += l1.illuminance * atm_transmittance_to_light(r, mu1, l1.angular_radius) * max(mu1, 0.0);
#endif
  return atm.medium.ground_albedo / ATM_PI * e;
}

// Light of the higher orders reflected by the Lambertian ground at planet-centred point p (the
// multi-scattering LUT's sky above the ground), before the multiple-scattering factor.
vec3 atm_ground_sky_light(vec3 p, AtmLight l0, AtmLight l1) {
  AtmParams P = atm_params();
  vec3 n = normalize(p);
  vec3 e = l0.illuminance * atm_multiscattering_ground(P, dot(n, l0.direction));
#if ATM_MOON_LIGHT
  if (atm_light_on(l1)) e += l1.illuminance * atm_multiscattering_ground(P, dot(n, l1.direction));
#endif
  return atm.medium.ground_albedo * e;
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
                       AtmLight l0, AtmLight l1, float ms_weight) {
  AtmMarch m = atm_march_start();
  vec3 iv = atm_ray_interval(origin, dir, max_t);
  if (iv.y <= iv.x) return m;
  atm_march_segment(m, origin, dir, iv.x, iv.y, steps, quadratic, l0, l1, ms_weight);
  if (ground && iv.z > 0.5) {
    vec3 g = origin + dir * iv.y;
    m.luminance += m.transmittance * atm_ground_luminance(g, l0, l1);
    // The ground's sky light of the higher orders, and its share of Hillaire's transfer f_ms next to
    // the air's T sigma_s: a Lambertian ground under a uniform radiance field L returns albedo L.
    if (ms_weight > 0.0) m.luminance += m.transmittance * ms_weight * atm_ground_sky_light(g, l0, l1);
    m.ms_transfer += m.transmittance * atm.medium.ground_albedo;
  }
  return m;
}

// In-scattering and transmittance between the origin and a surface at distance t (km): the ground
// does not end it (the surface is in front of whatever the ideal sphere says), only the top does.
AtmMarch atm_march_to_surface(vec3 origin, vec3 dir, float t, int steps, AtmLight l0, AtmLight l1) {
  AtmMarch m = atm_march_start();
  vec2 top = atm_ray_sphere(origin, dir, atm_top());
  float t0 = max(top.x, 0.0), t1 = min(top.y, t);
  if (t1 > t0) atm_march_segment(m, origin, dir, t0, t1, steps, false, l0, l1, atm_ms_factor());
  return m;
}

// The scene's lights from the uniform block (the moon only when it lights the sky).
AtmLight atm_sun_light() {
  return AtmLight(atm.sun_direction, atm.sun_illuminance, atm.sun_angular_radius_rad);
}
AtmLight atm_moon_light_source() {
  return AtmLight(atm.moon_direction, atm.moon_lights_sky > 0.5 ? atm.moon_illuminance : vec3(0.0),
                  atm.moon_angular_radius_rad);
}

// Camera position used by marches: moved up to the ground when under it.
vec3 atm_camera() { return atm.camera_km; }
