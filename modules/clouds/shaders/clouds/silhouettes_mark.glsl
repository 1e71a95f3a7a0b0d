#pragma once
// Which march pixels lie next to the last frame's silhouettes (issue 35): where the last resolved
// frame, reprojected, changes its opacity by more than u_silhouette_opacity within the 3 x 3 pixels
// around and the view moved, a pixel that this frame's march did not take (not its block's pixel this
// frame) is marched now (silhouettes_mark.comp lists it, march_silhouettes.comp marches the list)
// instead of being left to the resolve's history, which trails a moving silhouette by up to a whole
// cycle of the blocks. Where the pixel's clouds were out of the last frame's view, the four fresh
// samples around it decide.
#include "clouds/reproject.glsl"
// The last resolved frame (colour, transmittance) at its own size.
layout(binding = CLOUDS_UNIT_SILHOUETTE_HISTORY) uniform sampler2D u_silhouette_history;
// This frame's march, one pixel of each block: colour and transmittance, and its distances (m).
layout(binding = CLOUDS_UNIT_SILHOUETTE_CURRENT) uniform sampler2D u_silhouette_current;
layout(binding = CLOUDS_UNIT_SILHOUETTE_DISTANCE) uniform sampler2D u_silhouette_distance;
uniform float u_silhouette_opacity;
uniform float u_silhouette_motion_px;
uniform ivec2 u_silhouette_size;  // the march's whole size
// The block's size and the pixel of it marched this frame (as clouds/march_pixel.glsl's).
uniform ivec3 u_stride_offset;

// Whether march pixel `pixel` lies next to a silhouette and was not marched this frame.
bool clouds_at_silhouette(ivec2 pixel) {
  int n = u_stride_offset.x;
  if (all(equal(pixel % n, u_stride_offset.yz))) return false;
  ivec2 size = textureSize(u_silhouette_distance, 0);
  vec2 fresh_pos = vec2(pixel - u_stride_offset.yz) / float(n);  // in the march's texels
  ivec2 nearest = clamp(ivec2(floor(fresh_pos + 0.5)), ivec2(0), size - 1);
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(u_silhouette_size) * 2.0 - 1.0;
  vec2 uv = previous_uv(ndc, texelFetch(u_silhouette_distance, nearest, 0).r);
  float lo = 1.0, hi = 0.0;
  if (in_view(uv)) {
    ivec2 history_size = textureSize(u_silhouette_history, 0);
    // A view that did not move (by less than u_silhouette_motion_px of the history's pixels) keeps
    // its silhouettes where they were: the history holds them.
    vec2 moved = uv * vec2(history_size) - (vec2(pixel) + 0.5) * vec2(history_size) / vec2(u_silhouette_size);
    if (max(abs(moved.x), abs(moved.y)) < u_silhouette_motion_px) return false;
    ivec2 centre = ivec2(floor(uv * vec2(history_size)));
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        ivec2 q = clamp(centre + ivec2(x, y), ivec2(0), history_size - 1);
        float t = texelFetch(u_silhouette_history, q, 0).a;
        lo = min(lo, t), hi = max(hi, t);
      }
  } else {
    ivec2 corner = ivec2(floor(fresh_pos));
    for (int y = 0; y <= 1; ++y)
      for (int x = 0; x <= 1; ++x) {
        float t = texelFetch(u_silhouette_current, clamp(corner + ivec2(x, y), ivec2(0), size - 1), 0).a;
        lo = min(lo, t), hi = max(hi, t);
      }
  }
  return hi - lo > u_silhouette_opacity;
}
