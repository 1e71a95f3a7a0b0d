// Multi-scattering LUT (Hillaire 2020, section 5.5): for each (sun zenith, altitude), the second
// order luminance L2 and the transfer f_ms of an isotropic medium, averaged over 64 directions on
// the sphere (one invocation each), give psi_ms = L2 / (1 - f_ms) for an illuminance of 1.
#include "atmosphere/integrate.glsl"
layout(local_size_x = 64) in;
layout(rgba16f, binding = 0) uniform writeonly image2D o_lut;
shared vec3 s_luminance[64];
shared vec3 s_transfer[64];

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

  AtmMarch m = atm_march_ray(origin, dir, 1e30, atm_multiscattering_size.y, false, true, sun, none, true);
  s_luminance[i] = m.luminance;
  s_transfer[i] = m.ms_transfer;
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (i < stride) {
      s_luminance[i] += s_luminance[i + stride];
      s_transfer[i] += s_transfer[i + stride];
    }
    barrier();
  }
  if (i == 0u) {
    // The isotropic phase is inside the march; the average over the sphere is the second 1/(4 pi).
    vec3 l2 = s_luminance[0] / 64.0;
    vec3 f_ms = clamp(s_transfer[0] / 64.0, vec3(0.0), vec3(0.999));  // bounded geometric series
    imageStore(o_lut, texel, vec4(atm_fit_half(l2 / (1.0 - f_ms)), 1.0));
  }
}
