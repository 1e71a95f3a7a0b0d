#pragma once
// Everything the atmosphere shaders share: the uniform block (blocks.glsl.h, C++ includes it too), the LUT
// samplers at the units the runtime's light environment assigned (WELKIN_UNIT_*), the medium, phase
// functions, ray geometry and the LUT parameterisations. Lengths are km in a planet-centred frame whose axes
// are the scene's (x east, y north, z up).
#define ATM_PI 3.14159265358979

#include "atmosphere/blocks.glsl.h"

layout(std140, binding = WELKIN_BLOCK_ATMOSPHERE) uniform WelkinAtmosphere { AtmosphereFrameGpu atm; };

layout(binding = WELKIN_UNIT_ATMOSPHERE_TRANSMITTANCE) uniform sampler2D atm_transmittance_lut;
layout(binding = WELKIN_UNIT_ATMOSPHERE_MULTISCATTERING) uniform sampler2D atm_multiscattering_lut;
layout(binding = WELKIN_UNIT_ATMOSPHERE_SKY_VIEW) uniform sampler2D atm_sky_view_lut;
layout(binding = WELKIN_UNIT_ATMOSPHERE_AERIAL_INSCATTERING) uniform sampler3D atm_aerial_inscattering;
layout(binding = WELKIN_UNIT_ATMOSPHERE_AERIAL_TRANSMITTANCE) uniform sampler3D atm_aerial_transmittance;
layout(binding = WELKIN_UNIT_ATMOSPHERE_SKY_IRRADIANCE) uniform sampler2D atm_sky_irradiance_sh;

float atm_bottom() { return atm.medium.bottom_radius_km; }
float atm_top() { return atm.medium.top_radius_km; }
bool atm_camera_in_space() { return atm.camera_in_space > 0.5; }

// What the marching loops read of the block, loaded into registers once per invocation: software
// rasterisers reload uniform-block values at every use inside a loop, which made the medium alone
// cost four times its arithmetic. Functions taking an AtmParams are the loops' versions; those
// without load it themselves (for one-off use by materials).
struct AtmProfileParams {
  AtmosphereDensityLayerGpu lower, upper;
};

struct AtmParams {
  AtmProfileParams rayleigh_density, mie_density, absorption_density;
  vec3 rayleigh_scattering, mie_scattering, mie_extinction, absorption_extinction;
  float bottom, top, horizon_distance, thickness;  // horizon_distance: sqrt(top^2 - bottom^2)
  float lift;                                      // samples stay this far above the ground
  float ms_factor;
  vec2 transmittance_size;
  float multiscattering_size;
  vec2 mie_moments;
};

AtmParams atm_params() {
  AtmosphereMediumGpu m = atm.medium;
  return AtmParams(AtmProfileParams(m.rayleigh_density[0], m.rayleigh_density[1]),
                   AtmProfileParams(m.mie_density[0], m.mie_density[1]),
                   AtmProfileParams(m.absorption_density[0], m.absorption_density[1]), m.rayleigh_scattering,
                   m.mie_scattering, m.mie_extinction, m.absorption_extinction, m.bottom_radius_km,
                   m.top_radius_km, m.horizon_distance_km, m.thickness_km, m.lift_km,
                   m.multiple_scattering_factor, vec2(atm.transmittance_width, atm.transmittance_height),
                   float(atm.multiscattering_size), vec2(m.mie_moment_1, m.mie_moment_2));
}

// ---- Medium ------------------------------------------------------------------------------------

float atm_layer(AtmosphereDensityLayerGpu l, float h) {
  // min(.., 80) keeps exp finite, so an absent exponential (exp_term 0) adds exactly 0; the clamp
  // bounds the rest. No branch: software rasterisers run both sides of one.
  float exponential = l.exp_term * exp(min(l.exp_scale_per_km * h, 80.0));
  return clamp(l.linear_term_per_km * h + l.constant_term + exponential, 0.0, 1.0);
}

// The layer is chosen before evaluating it: one exp per profile instead of two.
float atm_profile(AtmProfileParams p, float h) {
  return atm_layer(h < p.lower.width_km ? p.lower : p.upper, h);
}

struct AtmMedium {
  vec3 rayleigh;    // scattering
  vec3 mie;         // scattering
  vec3 extinction;  // Rayleigh + Mie extinction + absorption
};

// Coefficients at altitude h (km); zero above the top so rays may run past it.
AtmMedium atm_medium(AtmParams P, float h) {
  AtmMedium m;
  float inside = h <= P.thickness ? 1.0 : 0.0;
  h = max(h, 0.0);
  float dr = atm_profile(P.rayleigh_density, h) * inside, dm = atm_profile(P.mie_density, h) * inside;
  float da = atm_profile(P.absorption_density, h) * inside;
  m.rayleigh = P.rayleigh_scattering * dr;
  m.mie = P.mie_scattering * dm;
  m.extinction = m.rayleigh + P.mie_extinction * dm + P.absorption_extinction * da;
  return m;
}
AtmMedium atm_medium(float h) { return atm_medium(atm_params(), h); }

// ---- Phase functions (1/sr; cos_theta between propagation directions, i.e. dot(view, light)) -----

float atm_rayleigh_phase(float c) { return 3.0 / (16.0 * ATM_PI) * (1.0 + c * c); }

float atm_hg_phase(float g, float c) {
  // 1 + g^2 - 2gc as a sum of non-negative terms keeps precision in the peak when |g| -> 1.
  float base = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - c)
                         : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + c);
  base = max(base, 1e-12);
  return (1.0 - g * g) / (4.0 * ATM_PI * base * sqrt(base));
}

float atm_mie_phase(float c) {
  float g = atm.medium.mie_g;
  if (atm.medium.mie_phase > 0.5) return atm_hg_phase(g, c);
  // Cornette-Shanks: HG times 3/2 (1 + c^2) / (2 + g^2), still normalised.
  return atm_hg_phase(g, c) * 1.5 * (1.0 + c * c) / (2.0 + g * g);
}

// ---- Ray geometry -------------------------------------------------------------------------------

// Near and far distances to a sphere about the planet centre; (-1, -1) when the line misses it.
// Well-conditioned for grazing rays: the discriminant uses the ray's closest approach.
vec2 atm_ray_sphere(vec3 o, vec3 d, float radius) {
  float b = dot(o, d);
  float q = length(o - b * d);
  float disc = (radius - q) * (radius + q);
  if (disc < 0.0) return vec2(-1.0);
  float s = sqrt(disc);
  float r = length(o);
  float c = (r - radius) * (r + radius);
  float k = b >= 0.0 ? -b - s : -b + s;
  if (k == 0.0) return vec2(0.0);
  float t1 = k, t2 = c / k;
  return vec2(min(t1, t2), max(t1, t2));
}

// True when a ray from radius r with zenith cosine mu meets the ground.
bool atm_hits_ground(float r, float mu) {
  float b = atm_bottom();
  return mu < 0.0 && r * r * (mu * mu - 1.0) + b * b >= 0.0;
}

float atm_distance_to_top(AtmParams P, float r, float mu) {
  float disc = r * r * (mu * mu - 1.0) + P.top * P.top;
  return max(0.0, -r * mu + sqrt(max(disc, 0.0)));
}
float atm_distance_to_top(float r, float mu) { return atm_distance_to_top(atm_params(), r, mu); }

// ---- LUT parameterisations (Bruneton 2017 / Hillaire 2020) -------------------------------------

// Texel centres at the ends of [0, 1]: the LUT holds exactly its domain's boundary values. The two
// are exact inverses (texel i's centre holds the parameter i / (size - 1); lut_mapping.h, tested).
float atm_unit_to_sub_uv(float u, float size) { return (0.5 + u * (size - 1.0)) / size; }
float atm_sub_uv_to_unit(float u, float size) { return (u - 0.5 / size) * (size / (size - 1.0)); }

// Transmittance to the top: x_r = rho / H and x_mu = the distance to the top normalised between
// its minimum (straight up) and maximum (the horizon), so the horizon is a texel row, not a smear.
vec2 atm_transmittance_uv(AtmParams P, float r, float mu) {
  float H = P.horizon_distance, b = P.bottom;
  float rho = sqrt(max(0.0, (r - b) * (r + b)));
  float d = atm_distance_to_top(P, r, mu);
  float d_min = P.top - r, d_max = rho + H;
  float x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  float x_r = rho / H;
  return vec2(atm_unit_to_sub_uv(clamp(x_mu, 0.0, 1.0), P.transmittance_size.x),
              atm_unit_to_sub_uv(clamp(x_r, 0.0, 1.0), P.transmittance_size.y));
}

vec2 atm_transmittance_r_mu(vec2 uv) {
  float x_mu = atm_sub_uv_to_unit(uv.x, float(atm.transmittance_width));
  float x_r = atm_sub_uv_to_unit(uv.y, float(atm.transmittance_height));
  float H = atm.medium.horizon_distance_km, b = atm_bottom();
  float rho = H * x_r;
  float r = sqrt(rho * rho + b * b);
  float d_min = atm_top() - r, d_max = rho + H;
  float d = d_min + x_mu * (d_max - d_min);
  float mu = d <= 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
  return vec2(r, clamp(mu, -1.0, 1.0));
}

// Transmittance from radius r along zenith cosine mu to the top (the ray must not hit the ground).
vec3 atm_transmittance(AtmParams P, float r, float mu) {
  return texture(atm_transmittance_lut, atm_transmittance_uv(P, r, mu)).rgb;
}
vec3 atm_transmittance(float r, float mu) { return atm_transmittance(atm_params(), r, mu); }

// Fraction of a light's disc above the planet's horizon at radius r (Bruneton's smooth horizon).
float atm_light_visibility(AtmParams P, float r, float mu_l, float angular_radius) {
  float sin_h = min(P.bottom / r, 1.0);
  float cos_h = -sqrt(max(0.0, 1.0 - sin_h * sin_h));
  float w = sin_h * max(angular_radius, 1e-4);
  return smoothstep(-w, w, mu_l - cos_h);
}

// Transmittance from planet-centred `origin` along unit v out of the atmosphere (from where the ray
// enters it, for an origin in space); 0 when the planet is in the way. For what lies beyond the air:
// discs and stars.
vec3 atm_transmittance_to_space(vec3 origin, vec3 v) {
  if (atm_ray_sphere(origin, v, atm_bottom()).y > 0.0) return vec3(0.0);
  vec2 top = atm_ray_sphere(origin, v, atm_top());
  if (!(top.y > 0.0)) return vec3(1.0);
  vec3 p = origin + v * max(top.x, 0.0);
  float r = length(p);
  return atm_transmittance(r, dot(p, v) / r);
}

// Direct light reaching radius r from a light at zenith cosine mu_l, shadowed by the planet.
vec3 atm_transmittance_to_light(AtmParams P, float r, float mu_l, float angular_radius) {
  return atm_transmittance(P, r, mu_l) * atm_light_visibility(P, r, mu_l, angular_radius);
}
vec3 atm_transmittance_to_light(float r, float mu_l, float angular_radius) {
  return atm_transmittance_to_light(atm_params(), r, mu_l, angular_radius);
}

// Multi-scattering LUT: v = altitude, linear as in Hillaire 2020 (section 5.5); u = mu_s under a
// signed square root, texels crowded towards the horizon. Across the terminator the light falls by
// orders of magnitude within a few hundredths of mu_s, which Hillaire's linear u spreads over one
// texel: bilinear interpolation of that fall made a setting sun's horizon up to 22% too blue
// against the path tracer at 32 texels. The square root puts the first texel beside mu_s = 0 at
// 1/n^2 of it instead of 2/n.
float atm_multiscattering_mu_s_to_unit(float mu_s) {
  return 0.5 + 0.5 * sign(mu_s) * sqrt(min(abs(mu_s), 1.0));
}
float atm_multiscattering_unit_to_mu_s(float x) {
  float s = 2.0 * x - 1.0;
  return sign(s) * s * s;
}

vec2 atm_multiscattering_uv(AtmParams P, float r, float mu_s) {
  float n = P.multiscattering_size;
  return vec2(atm_unit_to_sub_uv(atm_multiscattering_mu_s_to_unit(mu_s), n),
              atm_unit_to_sub_uv(clamp((r - P.bottom) / P.thickness, 0.0, 1.0), n));
}

// The LUT holds five square layers side by side (multiscattering_lut.comp): the scattered light
// arriving at a point, L(w) = c0 + a.w + w^T Q w (w towards where the light comes from), in the
// point's frame: z up, y towards the sun's azimuth. Layer 0 holds log c0 and Q_yz / c0 (one ratio
// for all channels), layer 1 a_z / c0 and Q_zz / c0 of red, layer 2 a_y / c0 and Q_zz / c0 of green,
// layer 3 Q_yy / c0 and Q_zz / c0 of blue (Q is traceless), layer 4 the irradiance / pi a horizontal
// surface receives, over c0. The terms toward the sun's azimuth matter in the planet's shadow: there
// the light comes from the sunlit air on one side, and Rayleigh scatters it forward and back twice
// as much as sideways; kept only about the vertical (averaged over azimuth), the anti-sun sky at dusk
// came out up to 38% too dark against the path tracer. Interpolating log c0 is exact where light
// falls exponentially, as it does into the planet's shadow; interpolated linearly, a dusk sky's
// multiple scattering came out 29% RMSE off instead of 10%. Each layer has a one-texel gutter on
// either side holding copies of its edge texels: texture units blend with 8-bit weights, so even a
// tap at a texel's centre takes up to 1/256 of its neighbour.
#define ATM_MS_LAYERS 5.0
vec4 atm_multiscattering_layer(AtmParams P, vec2 uv, float layer) {
  float n = P.multiscattering_size;
  float x = layer * (n + 2.0) + 1.0 + uv.x * n;
  return texture(atm_multiscattering_lut, vec2(x / (ATM_MS_LAYERS * (n + 2.0)), uv.y));
}

// Scattered light of every order, in-scattered towards the march direction d by the medium, per
// unit illuminance; mu_v = d.up, nu = d.(towards the light). By Funk-Hecke a phase function with
// Legendre moments lambda_l scales the field's part of degree l by lambda_l, evaluated at d:
// Rayleigh's are (1, 0, 1/10), Mie's come from the block. The truncated series can dip below zero
// looking away from a bright hemisphere through a forward-peaked phase; the clamp keeps the source
// physical there.
vec3 atm_multiscattering_source(AtmParams P, float r, float mu_s, float mu_v, float nu, AtmMedium med) {
  vec2 uv = atm_multiscattering_uv(P, r, mu_s);
  vec4 log_c0_kyz = atm_multiscattering_layer(P, uv, 0.0);
  vec4 az_kzz_r = atm_multiscattering_layer(P, uv, 1.0);
  vec4 ay_kzz_g = atm_multiscattering_layer(P, uv, 2.0);
  vec4 kyy_kzz_b = atm_multiscattering_layer(P, uv, 3.0);
  // d's component towards the light's azimuth; the terms that use it vanish with a vertical light.
  float z = mu_v;
  float y = clamp((nu - mu_v * mu_s) * inversesqrt(max(1.0 - mu_s * mu_s, 1e-12)), -1.0, 1.0);
  // d^T Q d with Q_xx = -Q_yy - Q_zz and x^2 = 1 - y^2 - z^2.
  vec3 k_zz = vec3(az_kzz_r.a, ay_kzz_g.a, kyy_kzz_b.a);
  vec3 quadrupole = k_zz * (2.0 * z * z + y * y - 1.0) + kyy_kzz_b.rgb * (2.0 * y * y + z * z - 1.0) +
                    2.0 * log_c0_kyz.a * y * z;
  vec3 dipole = az_kzz_r.rgb * z + ay_kzz_g.rgb * y;
  vec3 rayleigh = 1.0 + 0.1 * quadrupole;
  vec3 mie = 1.0 + P.mie_moments.y * quadrupole + P.mie_moments.x * dipole;
  return exp(log_c0_kyz.rgb) * max(med.rayleigh * rayleigh + med.mie * mie, vec3(0.0));
}

// Sky light of the scattered orders on the ground, as irradiance / pi for an illuminance of 1.
vec3 atm_multiscattering_ground(AtmParams P, float mu_s) {
  vec2 uv = atm_multiscattering_uv(P, P.bottom + P.lift, mu_s);
  return exp(atm_multiscattering_layer(P, uv, 0.0).rgb) * atm_multiscattering_layer(P, uv, 4.0).rgb;
}

// Sky-view LUT (Hillaire 2020's layout: horizon at v = 0.5, texels crowded towards it from both
// sides under a square root; the sun's azimuth at u = 0.5, texels crowded towards it). The angles go
// through pseudo-angles with exact inverses instead of acos and atan, because the sky pass evaluates
// this for every pixel and software rasterisers expand inverse trigonometry into long polynomials:
//   v: the angle e from the horizon (positive upwards) as t = tan(e / 2), linear near the horizon,
//      over its value at the zenith (above) or the nadir (below);
//   u: the azimuth phi from the sun as q = 1 - x / (|x| + |y|), which runs from 0 to 2 as phi runs
//      from 0 to pi and is linear near 0.
// The block's sky_view_* fields hold the mapping's constants for this camera (beta: the horizon's
// angle from the nadir). lut_mapping.h mirrors this on the CPU.
vec2 atm_sky_view_uv_local(vec3 d) {  // d in the LUT's frame, any length
  float h = length(d.xy), len = length(d);
  float sin_e = atm.sky_view_sin_beta * d.z + atm.sky_view_cos_beta * h;  // times |d|
  float cos_e = atm.sky_view_sin_beta * h - atm.sky_view_cos_beta * d.z;
  float k = sin_e / max(len + cos_e, 1e-30);
  k *= k >= 0.0 ? atm.sky_view_inv_tan_half_zenith_horizon : atm.sky_view_inv_tan_half_beta;
  float v = 0.5 - 0.5 * sign(k) * sqrt(min(abs(k), 1.0));
  float q = 1.0 - d.x / max(abs(d.x) + abs(d.y), 1e-30);
  float u = 0.5 + (d.y < 0.0 ? -0.5 : 0.5) * sqrt(0.5 * q);
  return vec2(u, v * atm.sky_view_v_scale + atm.sky_view_v_offset);
}

// Inverse of atm_sky_view_uv_local for a texel: (cos zenith, azimuth).
vec2 atm_sky_view_direction(vec2 uv) {
  float zenith_horizon = atm.sky_view_zenith_horizon, beta = atm.sky_view_beta;
  float c = 1.0 - 2.0 * atm_sub_uv_to_unit(uv.y, float(atm.sky_view_height));  // > 0 above the horizon
  float e = 2.0 * atan(c * abs(c) * tan(0.5 * (c >= 0.0 ? zenith_horizon : beta)));
  float s = 2.0 * uv.x - 1.0;
  float x = 1.0 - 2.0 * s * s;
  return vec2(cos(zenith_horizon - e), sign(s) * atan(1.0 - abs(x), x));
}

// World direction of a sky-view texel and back, through the frame at the camera.
vec3 atm_sky_view_world_direction(float cos_zenith, float azimuth) {
  float sin_zenith = sqrt(max(0.0, 1.0 - cos_zenith * cos_zenith));
  vec3 local = vec3(cos(azimuth) * sin_zenith, sin(azimuth) * sin_zenith, cos_zenith);
  return normalize(mat3(atm.sky_frame) * local);
}

// Luminance of the sky-view LUT along a direction (any length) in the LUT's frame (x towards the sun).
vec3 atm_sky_view_lookup_local(vec3 local) {
  return texture(atm_sky_view_lut, atm_sky_view_uv_local(local)).rgb;
}

vec3 atm_sky_view_lookup(vec3 world_dir) {
  return atm_sky_view_lookup_local(transpose(mat3(atm.sky_frame)) * world_dir);
}

// (1 - exp(-x)) / x without the cancellation at small x; the per-step energy-conserving integral.
vec3 atm_one_minus_exp_over_x(vec3 x) {
  vec3 series = 1.0 - x * (0.5 - x / 6.0);
  return mix((1.0 - exp(-x)) / max(x, vec3(1e-30)), series, lessThan(x, vec3(1e-3)));
}

// Largest RGBA16F value with the colour's hue kept (a per-channel clamp would turn the reddened sun
// grey). The frame targets have no pre-exposure, and the sun disc (~1.6e9 cd/m^2) exceeds it.
vec3 atm_fit_half(vec3 c) {
  float m = max(c.r, max(c.g, c.b));
  return m > 65504.0 ? c * (65504.0 / m) : c;
}
