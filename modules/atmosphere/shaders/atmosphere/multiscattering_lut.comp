// Multi-scattering LUT (Hillaire 2020, section 5.5): for each (sun zenith, altitude), psi_ms, the
// light of second and higher orders at a point as an isotropic source (sigma_s psi_ms is what the
// point scatters towards any direction), for an illuminance of 1: psi_ms = L2 / (1 - f_ms), L2 the
// mean over the sphere of the single-scattered light arriving at the point and f_ms the fraction of
// a uniform radiance field that comes back to it. 64 directions, one invocation each.
// Two departures from the paper, each measured against the path tracer (`welkin accuracy`, high
// quality, sun >= 3 degrees, all orders): L2 scatters the sun with the true phase functions rather
// than an isotropic one (it is exactly the second order's source), and f_ms counts the ground, which
// returns albedo L of a uniform field L as the air returns T sigma_s. As published: relative RMSE
// 5.8%, worst ray 25% (the blue of a low sun's horizon); with both: 3.2% and 13.5%. What remains is
// the isotropic treatment of the later orders itself.
#include "atmosphere/integrate.glsl"
layout(local_size_x = 64) in;
layout(rgba16f, binding = 0) uniform writeonly image2D o_lut;
shared vec3 s_luminance[64];
shared vec3 s_transfer[64];
shared vec3 s_upper[64];

void main() {
  ivec2 texel = ivec2(gl_WorkGroupID.xy);
  float n = float(atm_multiscattering_size.x);
  vec2 uv = (vec2(texel) + 0.5) / n;
  float mu_s = clamp(atm_sub_uv_to_unit(uv.x, n) * 2.0 - 1.0, -1.0, 1.0);
  float r = atm_bottom() + atm_ground_albedo.w + clamp(atm_sub_uv_to_unit(uv.y, n), 0.0, 1.0) *
                                               (atm_radii.w - atm_ground_albedo.w);
  vec3 origin = vec3(0.0, 0.0, r);
  AtmLight sun = AtmLight(vec3(0.0, sqrt(max(0.0, 1.0 - mu_s * mu_s)), mu_s), vec3(1.0), 0.0);
  AtmLight none = AtmLight(vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0);

  // A stratified 8x8 grid, uniform in solid angle.
  uint i = gl_LocalInvocationIndex;
  float a = (float(i / 8u) + 0.5) / 8.0, b = (float(i % 8u) + 0.5) / 8.0;
  float phi = 2.0 * ATM_PI * a, cos_theta = 1.0 - 2.0 * b;
  float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  vec3 dir = vec3(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);

  // No multi-scattering term (weight 0): this pass writes the LUT it would read.
  AtmMarch m = atm_march_ray(origin, dir, 1e30, atm_multiscattering_size.y, false, true, sun, none, 0.0);
  s_luminance[i] = m.luminance;
  s_transfer[i] = m.ms_transfer;
  // Irradiance / pi from the upper hemisphere: 4 cos theta per direction of a uniform 4 pi grid.
  s_upper[i] = m.luminance * 4.0 * max(cos_theta, 0.0);
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (i < stride) {
      s_luminance[i] += s_luminance[i + stride];
      s_transfer[i] += s_transfer[i + stride];
      s_upper[i] += s_upper[i + stride];
    }
    barrier();
  }
  if (i == 0u) {
    // Means over the sphere: the isotropic phase of the last scattering is the 1 / (4 pi).
    vec3 l2 = s_luminance[0] / 64.0;
    vec3 f_ms = clamp(s_transfer[0] / 64.0, vec3(0.0), vec3(0.999));  // bounded geometric series
    // Alpha: what a horizontal surface here receives of psi_ms (the sky above it, not the whole
    // sphere, whose lower half at the ground is the sun-lit ground itself), for the ground's sky light.
    float lum = dot(l2, vec3(1.0 / 3.0));
    float upper = lum > 0.0 ? dot(s_upper[0] / 64.0, vec3(1.0 / 3.0)) / lum : 1.0;
    imageStore(o_lut, texel, vec4(atm_fit_half(l2 / (1.0 - f_ms)), upper));
  }
}
