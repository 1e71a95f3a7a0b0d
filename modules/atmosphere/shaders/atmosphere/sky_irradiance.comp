// Sky irradiance for materials: the sky around the camera (sky-view LUT inside the atmosphere, a
// short march from space or with method raymarch: ATM_IRRADIANCE_MARCH) projected on L1 spherical
// harmonics, one 64-invocation group.
#include "atmosphere/integrate.glsl"
#ifndef ATM_IRRADIANCE_MARCH
#define ATM_IRRADIANCE_MARCH 0
#endif
layout(local_size_x = 64) in;
layout(rgba32f, binding = 0) uniform writeonly image2D o_sh;
shared vec3 s_sh[4][64];

vec3 sky_radiance(vec3 dir) {
#if ATM_IRRADIANCE_MARCH
  AtmLight sun = atm_sun_light(), moon = atm_moon_light_source();
  return atm_march_ray(atm_camera(), dir, 1e30, 8, false, true, sun, moon, atm_ms_factor()).luminance;
#else
  return atm_sky_view_lookup(dir);
#endif
}

void main() {
  uint i = gl_LocalInvocationIndex;
  vec3 sh[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  // 512 directions, equal-area (uniform in z and azimuth), 8 per invocation.
  for (uint k = 0u; k < 8u; ++k) {
    uint s = i * 8u + k;
    float z = 1.0 - 2.0 * (float(s / 32u) + 0.5) / 16.0;
    float phi = 2.0 * ATM_PI * (float(s % 32u) + 0.5) / 32.0;
    float q = sqrt(max(0.0, 1.0 - z * z));
    vec3 d = vec3(cos(phi) * q, sin(phi) * q, z);
    vec3 l = sky_radiance(d);
    sh[0] += l * 0.282095;
    sh[1] += l * 0.488603 * d.y;
    sh[2] += l * 0.488603 * d.z;
    sh[3] += l * 0.488603 * d.x;
  }
  for (int c = 0; c < 4; ++c) s_sh[c][i] = sh[c];
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1) {
    if (i < stride)
      for (int c = 0; c < 4; ++c) s_sh[c][i] += s_sh[c][i + stride];
    barrier();
  }
  if (i < 4u) imageStore(o_sh, ivec2(i, 0), vec4(s_sh[i][0] * (4.0 * ATM_PI / 512.0), 1.0));
}
