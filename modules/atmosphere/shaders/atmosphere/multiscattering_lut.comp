// Multi-scattering LUT (Hillaire 2020, section 5.5): for each (sun zenith, altitude), the scattered
// light of all orders arriving at a point, for an illuminance of 1, which every march scatters again
// towards its own direction (common.glsl, atm_multiscattering_source). 256 directions, one invocation
// each: Hillaire's 64 put the directions nearest the horizon 7 degrees off it, and a point in the
// planet's shadow at dusk is lit by a bright arch just above its horizon, which they missed (a dusk
// sky's red 39% too dark; the worst daylight ray 4.8% -> 3.4%). Hillaire keeps only the mean psi_ms
// and scatters it isotropically; this LUT also keeps the
// first two Legendre moments about the vertical, because the light coming up from a sunlit ground and
// down from the sky is far from isotropic, and Mie (forward) and Rayleigh (forward and backward)
// scatter it differently: as an isotropic source the ground's light made a high sun's red up to 6%
// too bright and its blue 3% too dark against the path tracer. Layers, side by side, each with a
// one-texel gutter either side (common.glsl, atm_multiscattering_layer), in floats: log c0 (c0 =
// psi_ms) with k2 = c2 / c0 (summed over channels) in alpha, c1 / c0, and the irradiance / pi from
// the upper hemisphere (the ground's sky light) over c0.
//
// ATM_MS_ITERATE 0, Hillaire's estimate: psi_ms = L2 / (1 - f_ms), L2 the mean of the single-scattered
// light arriving at the point and f_ms the fraction of a uniform radiance field that comes back to
// it. Two departures from the paper: L2 scatters the sun with the true phase functions (it is exactly
// the second order's source), and f_ms counts the ground, which returns albedo L of a uniform field L.
//
// ATM_MS_ITERATE 1, one pass of the fixed point psi = L2 + A psi: the same march, now also scattering
// the previous LUT's psi at every point it passes (and the ground's sky light from it), so each pass
// adds one order exactly where the geometric series assumed every point around to see the same
// light. That assumption fails where light changes fastest, near the terminator and the ground: with
// the estimate alone a low sun's horizon comes out up to 13.5% too blue-dark against the path tracer.
// The passes converge geometrically from the estimate (each one multiplies the remaining error by
// about f_ms < 1), so a few suffice; `multiscattering_iterations` sets how many.
#ifndef ATM_MS_ITERATE
#define ATM_MS_ITERATE 0
#endif
#include "atmosphere/integrate.glsl"
#define MS_N 16u             // directions per side of the stratified grid
#define MS_D (MS_N * MS_N)  // directions, one invocation each
layout(local_size_x = 256) in;
layout(rgba32f, binding = 0) uniform writeonly image2D o_lut;
shared vec3 s_moment[3][MS_D];
shared vec3 s_transfer[MS_D];
shared vec3 s_upper[MS_D];

void main() {
  ivec2 texel = ivec2(gl_WorkGroupID.xy);
  int size = atm_multiscattering_size.x;
  float n = float(size);
  vec2 uv = (vec2(texel) + 0.5) / n;
  float mu_s = clamp(atm_multiscattering_unit_to_mu_s(atm_sub_uv_to_unit(uv.x, n)), -1.0, 1.0);
  float r = atm_bottom() + atm_ground_albedo.w + clamp(atm_sub_uv_to_unit(uv.y, n), 0.0, 1.0) *
                                               (atm_radii.w - atm_ground_albedo.w);
  vec3 origin = vec3(0.0, 0.0, r);
  AtmLight sun = AtmLight(vec3(0.0, sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s), vec3(1.0), 0.0);
  AtmLight none = AtmLight(vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0);

  // A stratified grid, uniform in solid angle.
  uint i = gl_LocalInvocationIndex;
  float a = (float(i / MS_N) + 0.5) / float(MS_N), b = (float(i % MS_N) + 0.5) / float(MS_N);
  float phi = 2.0 * ATM_PI * a, cos_theta = 1.0 - 2.0 * b;
  float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  vec3 dir = vec3(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);

  // Weight 0 while estimating: the pass writes the LUT it would read. Weight 1 while iterating:
  // the LUT bound for reading is the previous pass's output, never this one's.
  AtmMarch m = atm_march_ray(origin, dir, 1e30, atm_multiscattering_size.y, false, true, sun, none,
                             float(ATM_MS_ITERATE));
  // The march's direction is where its light comes from: the moments (2l + 1) mean(L P_l(cos theta)).
  s_moment[0][i] = m.luminance;
  s_moment[1][i] = m.luminance * (3.0 * cos_theta);
  s_moment[2][i] = m.luminance * (5.0 * (1.5 * cos_theta * cos_theta - 0.5));
  s_transfer[i] = m.ms_transfer;
  // Irradiance / pi from the upper hemisphere: 4 cos theta per direction of a uniform 4 pi grid.
  s_upper[i] = m.luminance * 4.0 * max(cos_theta, 0.0);
  barrier();
  for (uint stride = MS_D / 2u; stride > 0u; stride >>= 1) {
    if (i < stride) {
      for (int l = 0; l < 3; ++l) s_moment[l][i] += s_moment[l][i + stride];
      s_transfer[i] += s_transfer[i + stride];
      s_upper[i] += s_upper[i + stride];
    }
    barrier();
  }
  if (i == 0u) {
#if ATM_MS_ITERATE
    vec3 scale = vec3(1.0 / float(MS_D));
#else
    // Hillaire's geometric series over the later orders, applied to every moment.
    vec3 f_ms = clamp(s_transfer[0] / float(MS_D), vec3(0.0), vec3(0.999));  // bounded
    vec3 scale = 1.0 / (float(MS_D) * (1.0 - f_ms));
#endif
    // A floor keeps the log finite where no light arrives at all (the ratios are then 0).
    vec3 c0 = max(s_moment[0][0] * scale, vec3(1e-30));
    float k2 = dot(s_moment[2][0] * scale, vec3(1.0)) / dot(c0, vec3(1.0));
    vec4 layer[3] = vec4[3](vec4(log(c0), k2), vec4(s_moment[1][0] * scale / c0, 1.0),
                            vec4(s_upper[0] * scale / c0, 1.0));
    for (int l = 0; l < 3; ++l) {
      // Layer l's texels start at l (size + 2) + 1; its edge texels are copied into its gutters.
      int x0 = l * (size + 2) + 1;
      vec4 value = layer[l];
      imageStore(o_lut, ivec2(x0 + texel.x, texel.y), value);
      if (texel.x == 0) imageStore(o_lut, ivec2(x0 - 1, texel.y), value);
      if (texel.x == size - 1) imageStore(o_lut, ivec2(x0 + size, texel.y), value);
    }
  }
}
