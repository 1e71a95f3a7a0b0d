#pragma once
// The tone map of one output pixel (tonemap.frag, tonemap.comp): one variant per curve (TONEMAPPER 0
// ACES, 1 AgX, 2 linear, clamped): a software rasteriser would otherwise evaluate every curve for every
// pixel and select one.
#include "welkin/tonemap.glsl"
layout(binding = 0) uniform sampler2D u_hdr;
uniform float u_exposure;
#if TONEMAP_UPSCALE
uniform vec2 u_output_size;  // the HDR colour is smaller: a moving view (Camera::moving_render_scale)
#endif

// `centre`: the output pixel's centre in pixels (gl_FragCoord.xy).
vec4 tonemap_pixel(vec2 centre) {
#if TONEMAP_UPSCALE
  // Bilinear: Catmull-Rom (five reads) cost 2.5 times as much here for no gain against the whole
  // frame (PSNR 41.3 against 41.5 dB on the demo at half size): the level of detail differs more.
  vec3 hdr = texture(u_hdr, centre / u_output_size).rgb * u_exposure;
#else
  vec3 hdr = texelFetch(u_hdr, ivec2(centre), 0).rgb * u_exposure;
#endif
  // A NaN or negative upstream must not turn into a black or white block on screen.
  hdr = clamp(hdr, vec3(0.0), vec3(65504.0));
#if TONEMAPPER == 0
  vec3 display = tonemap_aces(hdr);
#elif TONEMAPPER == 1
  vec3 display = tonemap_agx(hdr);
#else
  vec3 display = clamp(hdr, 0.0, 1.0);
#endif
  return vec4(linear_to_srgb(display), 1.0);
}
