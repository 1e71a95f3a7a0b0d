#pragma once
// World-space (camera-relative) view ray of a full-screen pixel, from the inverse view-projection.
vec3 view_ray_direction(mat4 inverse_view_projection, vec2 ndc) {
  vec4 far_point = inverse_view_projection * vec4(ndc, 0.5, 1.0);
  return normalize(far_point.xyz / far_point.w);
}
