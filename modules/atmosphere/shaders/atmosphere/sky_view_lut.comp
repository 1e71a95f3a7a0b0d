// Sky-view LUT (Hillaire 2020, section 5.3): the sky's luminance around the camera, every frame, in
// the camera's frame (see atm_sky_view_uv_local). Rays that reach the ground include the lit ground.
#include "atmosphere/integrate.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#ifndef ATM_RADIANCE_FORMAT
#define ATM_RADIANCE_FORMAT rgba16f  // rgba32f where the renderer measures (full precision)
#endif
layout(ATM_RADIANCE_FORMAT, binding = 0) uniform writeonly image2D o_lut;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(atm.sky_view_width, atm.sky_view_height);
  if (any(greaterThanEqual(texel, size))) return;
  vec2 uv = (vec2(texel) + 0.5) / vec2(size);
  vec2 zenith_azimuth = atm_sky_view_direction(uv);
  vec3 dir = atm_sky_view_world_direction(zenith_azimuth.x, zenith_azimuth.y);
  AtmMarch m = atm_march_ray(atm_camera(), dir, 1e30, atm.sky_view_steps, true, true, atm_sun_light(),
                             atm_moon_light_source(), atm_ms_factor());
  imageStore(o_lut, texel, vec4(atm_fit_half(m.luminance), 1.0));
}
