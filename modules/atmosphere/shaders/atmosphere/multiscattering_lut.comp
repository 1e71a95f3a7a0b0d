// Multi-scattering LUT (Hillaire 2020, section 5.5): for each (sun zenith, altitude), the scattered
// light of all orders arriving at a point, for an illuminance of 1, which every march scatters again
// towards its own direction (common.glsl, atm_multiscattering_source).
//
// Directions: 256, one invocation each, over the half of the sphere on the sun's side (the field is
// even across the sun's vertical plane, so each stands for its mirror image too), crowded towards
// the horizon. A point in the planet's shadow at dusk is lit by a bright arch just above its horizon:
// Hillaire's 64 directions lie 7 degrees off it at best, and a grid uniform in cos theta 3.6 degrees
// (the dusk sky 8.8% RMSE off the path tracer instead of 5.2%).
//
// What it keeps: Hillaire keeps only the mean psi_ms and scatters it isotropically. This LUT keeps
// the field's harmonics of degrees 0 to 2 in the point's frame (z up, y towards the sun's azimuth),
// because the light is far from isotropic and Mie (forward) and Rayleigh (forward and backward)
// scatter it differently: the light coming up from a sunlit ground (as an isotropic source it made
// a high sun's red up to 6% too bright), and at dusk the light from the sunlit air on the sun's side
// (kept only about the vertical, the anti-sun sky came out up to 38% too dark). Layers, side by side,
// each with a one-texel gutter either side (common.glsl, atm_multiscattering_layer), in floats.
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
#define MS_NPHI 8u                // azimuths over the half sphere
#define MS_NCOS 32u               // zenith cosines, half in each hemisphere
#define MS_D (MS_NPHI * MS_NCOS)  // directions, one invocation each
#define MS_MOMENTS 6
layout(local_size_x = 256) in;
layout(rgba32f, binding = 0) uniform writeonly image2D o_lut;
shared vec3 s_moment[MS_MOMENTS][MS_D];
shared vec3 s_transfer[MS_D];
shared vec3 s_upper[MS_D];

void main() {
  ivec2 texel = ivec2(gl_WorkGroupID.xy);
  int size = atm.multiscattering_size;
  float n = float(size);
  vec2 uv = (vec2(texel) + 0.5) / n;
  float mu_s = clamp(atm_multiscattering_unit_to_mu_s(atm_sub_uv_to_unit(uv.x, n)), -1.0, 1.0);
  float r = atm_bottom() + atm.medium.lift_km + clamp(atm_sub_uv_to_unit(uv.y, n), 0.0, 1.0) *
                                               (atm.medium.thickness_km - atm.medium.lift_km);
  vec3 origin = vec3(0.0, 0.0, r);
  AtmLight sun = AtmLight(vec3(0.0, sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s), vec3(1.0), 0.0);
  AtmLight none = AtmLight(vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0);

  // Uniform in azimuth and, in each hemisphere, uniform in u = sqrt|cos theta| with weights 2u du:
  // the nearest directions lie 0.06 degrees from the horizon.
  uint i = gl_LocalInvocationIndex;
  uint c = i % MS_NCOS;
  const float half_n = float(MS_NCOS / 2u);
  float phi = ATM_PI * ((float(i / MS_NCOS) + 0.5) / float(MS_NPHI) - 0.5);
  float u = (float(c % (MS_NCOS / 2u)) + 0.5) / half_n;
  float cos_theta = c < MS_NCOS / 2u ? u * u : -u * u;
  float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  vec3 dir = vec3(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);
  // This direction's share of the sphere: 2u / half_n of its hemisphere's cosines, over two
  // hemispheres and MS_NPHI azimuths.
  float weight = u / (half_n * float(MS_NPHI));

  // Weight 0 while estimating: the pass writes the LUT it would read. Weight 1 while iterating:
  // the LUT bound for reading is the previous pass's output, never this one's.
  AtmMarch m = atm_march_ray(origin, dir, 1e30, atm.multiscattering_steps, false, true, sun, none,
                             float(ATM_MS_ITERATE));
  // The march's direction is where its light comes from. Its projections on the harmonics of
  // degrees 0 to 2 that are even across the sun's vertical plane: L(w) = c0 + a.w + w^T Q w,
  // a = 3 mean(L w), Q = 5 mean(L (3/2 w w^T - 1/2)), traceless, so Q_zz, Q_yy and Q_yz hold it
  // (Q_xy = Q_xz = 0 by the symmetry).
  vec3 L = m.luminance * weight;
  s_moment[0][i] = L;
  s_moment[1][i] = L * (3.0 * dir.z);
  s_moment[2][i] = L * (5.0 * (1.5 * dir.z * dir.z - 0.5));
  s_moment[3][i] = L * (3.0 * dir.y);
  s_moment[4][i] = L * (7.5 * dir.y * dir.z);
  s_moment[5][i] = L * (5.0 * (1.5 * dir.y * dir.y - 0.5));
  s_transfer[i] = m.ms_transfer * weight;
  // Irradiance / pi from the upper hemisphere: 4 pi cos theta / pi of each direction's share.
  s_upper[i] = L * 4.0 * max(cos_theta, 0.0);
  barrier();
  for (uint stride = MS_D / 2u; stride > 0u; stride >>= 1) {
    if (i < stride) {
      for (int l = 0; l < MS_MOMENTS; ++l) s_moment[l][i] += s_moment[l][i + stride];
      s_transfer[i] += s_transfer[i + stride];
      s_upper[i] += s_upper[i + stride];
    }
    barrier();
  }
  if (i == 0u) {
#if ATM_MS_ITERATE
    vec3 scale = vec3(1.0);
#else
    // Hillaire's geometric series over the later orders, applied to every moment.
    vec3 f_ms = clamp(s_transfer[0], vec3(0.0), vec3(0.999));  // bounded
    vec3 scale = 1.0 / (1.0 - f_ms);
#endif
    // A floor keeps the log finite where no light arrives at all (the ratios are then 0).
    vec3 c0 = max(s_moment[0][0] * scale, vec3(1e-30));
    // Layer 0: log c0 and Q_yz / c0 (summed over channels); 1: a_z / c0 and Q_zz / c0 of red; 2: a_y / c0
    // and Q_zz / c0 of green; 3: Q_yy / c0 and Q_zz / c0 of blue; 4: the irradiance / pi from the
    // upper hemisphere (the ground's sky light) over c0. A march reads four layers.
    vec3 inv_c0 = scale / c0;
    vec3 k_zz = s_moment[2][0] * inv_c0;
    float k_yz = dot(s_moment[4][0] * scale, vec3(1.0)) / dot(c0, vec3(1.0));
    vec4 layer[5] = vec4[5](vec4(log(c0), k_yz), vec4(s_moment[1][0] * inv_c0, k_zz.r),
                            vec4(s_moment[3][0] * inv_c0, k_zz.g), vec4(s_moment[5][0] * inv_c0, k_zz.b),
                            vec4(s_upper[0] * inv_c0, 1.0));
    for (int l = 0; l < 5; ++l) {
      // Layer l's texels start at l (size + 2) + 1; its edge texels are copied into its gutters.
      int x0 = l * (size + 2) + 1;
      vec4 value = layer[l];
      imageStore(o_lut, ivec2(x0 + texel.x, texel.y), value);
      if (texel.x == 0) imageStore(o_lut, ivec2(x0 - 1, texel.y), value);
      if (texel.x == size - 1) imageStore(o_lut, ivec2(x0 + size, texel.y), value);
    }
  }
}
