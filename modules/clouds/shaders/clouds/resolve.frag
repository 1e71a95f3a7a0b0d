// The clouds' temporal resolve as a fragment pass (clouds/resolve_pixel.glsl).
#include "clouds/resolve_pixel.glsl"
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
layout(location = 1) out float o_depth;
#if CLOUDS_WITH_CLUSTERS
layout(location = 2) out vec4 o_with_clusters;
#endif
#if CLOUDS_CLEAR
layout(location = 2 + CLOUDS_WITH_CLUSTERS) out float o_clear;
#endif
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  o_color = resolved(pixel, v_ndc, o_depth);
#if CLOUDS_WITH_CLUSTERS
  o_with_clusters = with_clusters(pixel, o_color);
#endif
#if CLOUDS_CLEAR
  o_clear = resolved_clear(pixel);
#endif
}
