// The god rays and the haze applied to the frame in place, as a compute pass: frame x T_haze + (haze
// light - shafts) (godrays/apply.glsl). What the haze's light needs that is the same for every pixel
// (the sun's irradiance and the sky's at the camera) is found once per work group.
#define GODRAYS_APPLY_COMPUTE 1
#include "welkin/screen_pass.glsl"
#include "godrays/view_ray.glsl"
#include "godrays/apply.glsl"
#if GODRAYS_HAZE
#include "welkin/lighting.glsl"
#endif
layout(GODRAYS_COLOR_FORMAT, binding = 0) uniform image2D u_color;

void main() {
#if GODRAYS_HAZE
  if (gl_LocalInvocationIndex == 0u) {
    v_sun_irradiance = welkin_sun_irradiance(vec3(0.0));
    v_sky_radiance = (welkin_sky_irradiance(gr.up) + welkin_sky_irradiance(-gr.up)) / 12.5663706143592;
  }
  barrier();
#endif
  ivec2 pixel;
  if (!screen_pixel(pixel)) return;
  vec4 c = haze_and_shafts(screen_ndc(pixel, imageSize(u_color)), pixel);
  if (c == vec4(0.0, 0.0, 0.0, 1.0)) return;  // air whose sunlight nothing withholds, and no haze
  vec4 frame = imageLoad(u_color, pixel);
  imageStore(u_color, pixel, vec4(frame.rgb * c.a + c.rgb, frame.a));
}
