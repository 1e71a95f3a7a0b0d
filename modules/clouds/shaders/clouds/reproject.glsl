#pragma once
// Where the clouds seen through a pixel of this frame lay in the last frame's image (the temporal
// resolve and the march at silhouettes): the ray through ndc, at the clouds' distance along it, seen
// from the last frame's camera.
#include "welkin/view.glsl"
uniform mat4 u_inverse_view_projection;
uniform mat4 u_previous_view_projection;
uniform vec3 u_camera_moved_m;  // this frame's camera minus the last one's

// In the last frame's uv (outside [0, 1] where they were not in view).
vec2 previous_uv(vec2 ndc, float distance_m) {
  vec3 dir = view_ray_direction(u_inverse_view_projection, ndc);
  vec4 clip = u_previous_view_projection * vec4(dir * distance_m + u_camera_moved_m, 1.0);
  return clip.w <= 0.0 ? vec2(-1.0) : clip.xy / clip.w * 0.5 + 0.5;
}
bool in_view(vec2 uv) { return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))); }
