// Aerial-perspective froxels (Hillaire 2020, section 5.4): one invocation per screen-space column
// marches outwards once, storing in-scattering and transmittance at every slice centre; slice k
// lies at distance D ((k + 0.5) / N)^2, so nearby geometry gets most of the slices.
#include "atmosphere/integrate.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#ifndef ATM_RADIANCE_FORMAT
#define ATM_RADIANCE_FORMAT rgba16f  // rgba32f where the renderer measures (full precision)
#endif
layout(ATM_RADIANCE_FORMAT, binding = 0) uniform writeonly image3D o_inscattering;
layout(ATM_RADIANCE_FORMAT, binding = 1) uniform writeonly image3D o_transmittance;

void main() {
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  ivec2 columns = ivec2(atm.aerial_width, atm.aerial_height);
  if (any(greaterThanEqual(column, columns))) return;
  vec2 ndc = (vec2(column) + 0.5) / vec2(columns) * 2.0 - 1.0;
  vec4 far_point = atm.aerial_inverse_view_projection * vec4(ndc, 0.5, 1.0);
  vec3 dir = normalize(far_point.xyz / far_point.w);
  vec3 origin = atm_camera();
  AtmLight sun = atm_sun_light(), moon = atm_moon_light_source();
  AtmMarch m = atm_march_start();
  int slices = atm.aerial_slices, steps = atm.aerial_steps_per_slice;
  float depth_km = atm.aerial_distance_km;
  // The ground does not stop the march: geometry seen there (terrain below the ideal sphere) is in
  // front of it, and its air is ground-level air (atm_medium clamps the altitude). Each slice goes on
  // from the sample where the previous one ended.
  float w0 = 0.5 / float(slices);
  atm_march_segment(m, origin, dir, 0.0, depth_km * w0 * w0, steps, false, sun, moon, atm_ms_factor());
  imageStore(o_inscattering, ivec3(column, 0), vec4(atm_fit_half(m.luminance), 1.0));
  imageStore(o_transmittance, ivec3(column, 0), vec4(m.transmittance, 1.0));
  for (int k = 1; k < slices; ++k) {
    float w = (float(k) + 0.5) / float(slices);
    atm_march_segment_resume(m, origin, dir, depth_km * w * w, steps, sun, moon, atm_ms_factor());
    imageStore(o_inscattering, ivec3(column, k), vec4(atm_fit_half(m.luminance), 1.0));
    imageStore(o_transmittance, ivec3(column, k), vec4(m.transmittance, 1.0));
  }
}
