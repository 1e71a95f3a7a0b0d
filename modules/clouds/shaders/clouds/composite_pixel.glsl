#pragma once
// Lays the clouds over the frame (one body for composite.frag and composite.comp): the march (at a
// fraction of the frame's resolution, upsampled bilinearly: colour is premultiplied, so filtering it
// is exact) as colour + transmittance x behind, and with CLOUDS_WITH_CLUSTERS the mesh clusters behind
// it (premultiplied, opacity in alpha; magnified through a B-spline): march + T (clusters + (1 -
// opacity) behind). Where the temporal resolve ran it has laid them in already (resolve_pixel.glsl).
layout(binding = 0) uniform sampler2D u_clouds;
#if CLOUDS_WITH_CLUSTERS
#include "clouds/b_spline.glsl"
layout(binding = 1) uniform sampler2D u_clusters;
#endif
// What is laid over the frame at uv: colour, and the transmittance that scales what lies behind.
vec4 clouds_over(vec2 uv) {
  vec4 over = texture(u_clouds, uv);
#if CLOUDS_WITH_CLUSTERS
  vec4 c = clouds_b_spline(u_clusters, uv);
  over = vec4(over.rgb + over.a * c.rgb, over.a * (1.0 - c.a));
#endif
  return over;
}
