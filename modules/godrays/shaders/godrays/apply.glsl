#pragma once
// What the god rays and the haze make of a pixel of the frame: frame x T_haze + (haze light - shafts).
// The shafts are upsampled bilinearly: they vary slowly across the screen, and at silhouettes they
// spread over a few pixels (a depth-aware upsampling
// of four taps cost 4.9 copies of the frame against this one's 1.4-1.6). The haze is evaluated here, per
// pixel, in closed form: lit by the sun at the camera (its Henyey-Greenstein lobe) and the sky.
//   GODRAYS_SHAFTS: a shafts texture to subtract; GODRAYS_HAZE: the haze layer.
layout(binding = 0) uniform sampler2D u_loss;   // the shafts' light to take away
#if GODRAYS_HAZE
#include "godrays/haze.glsl"
layout(binding = 1) uniform sampler2D u_depth;  // the frame's
#ifdef GODRAYS_APPLY_COMPUTE
shared vec3 v_sun_irradiance;  // found once per work group (apply.comp)
shared vec3 v_sky_radiance;
#else
flat in vec3 v_sun_irradiance;  // at the camera (apply.vert)
flat in vec3 v_sky_radiance;
#endif
#endif

// rgb: the light to add (the haze's, less the shafts'), a: the haze's transmittance.
vec4 haze_and_shafts(vec2 ndc, ivec2 pixel) {
  vec3 light = vec3(0.0);
  float transmittance = 1.0;
#if GODRAYS_HAZE
  vec3 dir = view_ray_direction(gr.inverse_view_projection, ndc);
  float tau = haze_optical_depth(dir, scene_distance_m(u_depth, pixel, ndc));
  transmittance = exp(-tau);
  vec3 source = v_sun_irradiance * haze_phase(dot(dir, gr.sun_direction)) + v_sky_radiance;
  light = source * (gr.haze_scattering / haze_extinction_per_density()) * (1.0 - transmittance);
#endif
#if GODRAYS_SHAFTS
  light -= textureLod(u_loss, ndc * 0.5 + 0.5, 0.0).rgb;
#endif
  return vec4(light, transmittance);
}
