#pragma once
// Everything the atmosphere shaders share: the uniform block (src/uniforms.h mirrors it), the LUT
// samplers at fixed units, the medium, phase functions, ray geometry and the LUT parameterisations.
// Lengths are km in a planet-centred frame whose axes are the scene's (x east, y north, z up).
#define ATM_PI 3.14159265358979

layout(std140, binding = 7) uniform WelkinAtmosphere {
  vec4 atm_rayleigh_scattering;    // rgb 1/km
  vec4 atm_mie_scattering;         // rgb 1/km; w: g
  vec4 atm_mie_extinction;         // rgb 1/km; w: phase (0 Cornette-Shanks, 1 Henyey-Greenstein)
  vec4 atm_absorption_extinction;  // rgb 1/km; w: multiple-scattering factor
  vec4 atm_ground_albedo;          // rgb; w: lift keeping samples above the ground (km)
  vec4 atm_radii;                  // bottom, top, sqrt(top^2 - bottom^2), top - bottom
  vec4 atm_density[12];            // Rayleigh, Mie, ozone: per layer (width, exp, scale, linear), (constant)
  vec4 atm_camera_km;              // planet-centred camera; w: its radius
  vec4 atm_sun_direction;          // w: cos of the angular radius
  vec4 atm_sun_illuminance;        // lux outside the atmosphere; w: angular radius (rad)
  vec4 atm_moon_direction;
  vec4 atm_moon_illuminance;
  vec4 atm_moon_light;             // sunlight direction on the moon's face; w: illuminated fraction
  vec4 atm_flags;                  // sun disc, limb darkening, moon disc, moon lights the sky
  mat4 atm_inverse_view_projection;
  mat4 atm_view_projection;
  mat4 atm_sky_frame;              // sky-view LUT frame: x towards the sun's azimuth, z up at the camera
  ivec4 atm_transmittance_size;    // width, height, steps
  ivec4 atm_multiscattering_size;  // size, steps
  ivec4 atm_sky_view_size;         // width, height, steps
  ivec4 atm_aerial_size;           // width, height, slices, steps per slice
  vec4 atm_aerial_params;          // distance (km), raymarch steps, 1 when the camera is in space
};

layout(binding = 10) uniform sampler2D atm_transmittance_lut;
layout(binding = 11) uniform sampler2D atm_multiscattering_lut;
layout(binding = 12) uniform sampler2D atm_sky_view_lut;
layout(binding = 13) uniform sampler3D atm_aerial_inscattering;
layout(binding = 14) uniform sampler3D atm_aerial_transmittance;
layout(binding = 15) uniform sampler2D atm_sky_irradiance_sh;

float atm_bottom() { return atm_radii.x; }
float atm_top() { return atm_radii.y; }
bool atm_camera_in_space() { return atm_aerial_params.z > 0.5; }

// ---- Medium ------------------------------------------------------------------------------------

float atm_layer(vec4 l, float constant_term, float h) {
  float v = l.w * h + constant_term;
  // Skipping absent exponentials avoids 0 * inf for steep scales; the clamp bounds the rest.
  if (l.y != 0.0) v += l.y * exp(min(l.z * h, 80.0));
  return clamp(v, 0.0, 1.0);
}

float atm_profile(int p, float h) {
  vec4 l0 = atm_density[p * 4 + 0], l1 = atm_density[p * 4 + 2];
  return h < l0.x ? atm_layer(l0, atm_density[p * 4 + 1].x, h) : atm_layer(l1, atm_density[p * 4 + 3].x, h);
}

struct AtmMedium {
  vec3 rayleigh;    // scattering
  vec3 mie;         // scattering
  vec3 extinction;  // Rayleigh + Mie extinction + absorption
};

// Coefficients at altitude h (km); zero above the top so rays may run past it.
AtmMedium atm_medium(float h) {
  AtmMedium m;
  float inside = h <= atm_radii.w ? 1.0 : 0.0;
  h = max(h, 0.0);
  float dr = atm_profile(0, h) * inside, dm = atm_profile(1, h) * inside, da = atm_profile(2, h) * inside;
  m.rayleigh = atm_rayleigh_scattering.rgb * dr;
  m.mie = atm_mie_scattering.rgb * dm;
  m.extinction = m.rayleigh + atm_mie_extinction.rgb * dm + atm_absorption_extinction.rgb * da;
  return m;
}

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
  float g = atm_mie_scattering.w;
  if (atm_mie_extinction.w > 0.5) return atm_hg_phase(g, c);
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

float atm_distance_to_top(float r, float mu) {
  float t = atm_top();
  float disc = r * r * (mu * mu - 1.0) + t * t;
  return max(0.0, -r * mu + sqrt(max(disc, 0.0)));
}

// ---- LUT parameterisations (Bruneton 2017 / Hillaire 2020) -------------------------------------

// Texel centres at the ends of [0, 1]: the LUT holds exactly its domain's boundary values.
float atm_unit_to_sub_uv(float u, float size) { return (u + 0.5 / size) * (size / (size + 1.0)); }
float atm_sub_uv_to_unit(float u, float size) { return (u - 0.5 / size) * (size / (size - 1.0)); }

// Transmittance to the top: x_r = rho / H and x_mu = the distance to the top normalised between
// its minimum (straight up) and maximum (the horizon), so the horizon is a texel row, not a smear.
vec2 atm_transmittance_uv(float r, float mu) {
  float H = atm_radii.z, b = atm_bottom();
  float rho = sqrt(max(0.0, (r - b) * (r + b)));
  float d = atm_distance_to_top(r, mu);
  float d_min = atm_top() - r, d_max = rho + H;
  float x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  float x_r = rho / H;
  return vec2(atm_unit_to_sub_uv(clamp(x_mu, 0.0, 1.0), float(atm_transmittance_size.x)),
              atm_unit_to_sub_uv(clamp(x_r, 0.0, 1.0), float(atm_transmittance_size.y)));
}

vec2 atm_transmittance_r_mu(vec2 uv) {
  float x_mu = atm_sub_uv_to_unit(uv.x, float(atm_transmittance_size.x));
  float x_r = atm_sub_uv_to_unit(uv.y, float(atm_transmittance_size.y));
  float H = atm_radii.z, b = atm_bottom();
  float rho = H * x_r;
  float r = sqrt(rho * rho + b * b);
  float d_min = atm_top() - r, d_max = rho + H;
  float d = d_min + x_mu * (d_max - d_min);
  float mu = d <= 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
  return vec2(r, clamp(mu, -1.0, 1.0));
}

// Transmittance from radius r along zenith cosine mu to the top (the ray must not hit the ground).
vec3 atm_transmittance(float r, float mu) {
  return texture(atm_transmittance_lut, atm_transmittance_uv(r, mu)).rgb;
}

// Fraction of a light's disc above the planet's horizon at radius r (Bruneton's smooth horizon).
float atm_light_visibility(float r, float mu_l, float angular_radius) {
  float sin_h = min(atm_bottom() / r, 1.0);
  float cos_h = -sqrt(max(0.0, 1.0 - sin_h * sin_h));
  float w = sin_h * max(angular_radius, 1e-4);
  return smoothstep(-w, w, mu_l - cos_h);
}

// Direct light reaching radius r from a light at zenith cosine mu_l, shadowed by the planet.
vec3 atm_transmittance_to_light(float r, float mu_l, float angular_radius) {
  float v = atm_light_visibility(r, mu_l, angular_radius);
  return v > 0.0 ? atm_transmittance(r, mu_l) * v : vec3(0.0);
}

// Multi-scattering LUT: u = mu_s, v = altitude, both linear (Hillaire 2020, section 5.5).
vec2 atm_multiscattering_uv(float r, float mu_s) {
  float n = float(atm_multiscattering_size.x);
  return vec2(atm_unit_to_sub_uv(clamp(mu_s * 0.5 + 0.5, 0.0, 1.0), n),
              atm_unit_to_sub_uv(clamp((r - atm_bottom()) / atm_radii.w, 0.0, 1.0), n));
}

vec3 atm_multiscattering(float r, float mu_s) {
  return texture(atm_multiscattering_lut, atm_multiscattering_uv(r, mu_s)).rgb;
}

// Sky-view LUT: u = azimuth from the sun over the whole circle (signed square root: fine near the
// sun), v = zenith angle with the horizon at v = 0.5 and texels squeezed towards it from both sides.
vec2 atm_sky_view_uv(float r, float cos_zenith, float azimuth) {
  float b = atm_bottom();
  float cos_beta = sqrt(max(0.0, (r - b) * (r + b))) / r;
  float beta = acos(clamp(cos_beta, -1.0, 1.0));
  float zenith_horizon = ATM_PI - beta;
  float zenith = acos(clamp(cos_zenith, -1.0, 1.0));
  float v;
  if (zenith < zenith_horizon) {
    float c = sqrt(max(0.0, 1.0 - zenith / zenith_horizon));
    v = 0.5 * (1.0 - c);
  } else {
    float c = sqrt(clamp((zenith - zenith_horizon) / max(beta, 1e-6), 0.0, 1.0));
    v = 0.5 + 0.5 * c;
  }
  float a = clamp(azimuth / ATM_PI, -1.0, 1.0);
  float u = 0.5 + 0.5 * sign(a) * sqrt(abs(a));
  return vec2(u, atm_unit_to_sub_uv(v, float(atm_sky_view_size.y)));
}

// Inverse of atm_sky_view_uv for a texel: (cos zenith, azimuth).
vec2 atm_sky_view_direction(float r, vec2 uv) {
  float b = atm_bottom();
  float cos_beta = sqrt(max(0.0, (r - b) * (r + b))) / r;
  float beta = acos(clamp(cos_beta, -1.0, 1.0));
  float zenith_horizon = ATM_PI - beta;
  float v = atm_sub_uv_to_unit(uv.y, float(atm_sky_view_size.y));
  float zenith;
  if (v < 0.5) {
    float c = 1.0 - 2.0 * v;
    zenith = zenith_horizon * (1.0 - c * c);
  } else {
    float c = 2.0 * v - 1.0;
    zenith = zenith_horizon + beta * c * c;
  }
  float s = 2.0 * uv.x - 1.0;
  return vec2(cos(zenith), sign(s) * s * s * ATM_PI);
}

// World direction of a sky-view texel and back, through the frame at the camera.
vec3 atm_sky_view_world_direction(float cos_zenith, float azimuth) {
  float sin_zenith = sqrt(max(0.0, 1.0 - cos_zenith * cos_zenith));
  vec3 local = vec3(cos(azimuth) * sin_zenith, sin(azimuth) * sin_zenith, cos_zenith);
  return normalize(mat3(atm_sky_frame) * local);
}

vec3 atm_sky_view_lookup(vec3 world_dir) {
  vec3 local = transpose(mat3(atm_sky_frame)) * world_dir;
  float azimuth = atan(local.y, local.x);
  return texture(atm_sky_view_lut, atm_sky_view_uv(atm_camera_km.w, local.z, azimuth)).rgb;
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
