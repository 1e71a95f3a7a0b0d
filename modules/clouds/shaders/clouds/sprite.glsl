#pragma once
// A quad facing the camera that covers a sphere (six vertices, gl_VertexID 0-5): the cone of rays
// that touch it, at the centre's distance; the whole screen when the camera is near or inside it.
// Returns the corner camera-relative (m, on the pixel's ray) and its clip position.
uniform mat4 u_view_projection;  // camera-relative
uniform mat4 u_inverse_view_projection;

vec3 sprite_corner(vec3 centre, float r, int vertex, out vec4 clip) {
  const vec2 corners[6] =
      vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 corner = corners[vertex];
  float d = length(centre);
  if (d < 2.0 * r) {
    clip = vec4(corner, 0.5, 1.0);
    vec4 p = u_inverse_view_projection * clip;
    return p.xyz / p.w;
  }
  // The cone of rays that touch the sphere is r d / sqrt(d^2 - r^2) wide at the centre's distance.
  vec3 forward = centre / d;
  vec3 right = normalize(cross(forward, abs(forward.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 up = cross(right, forward);
  float h = r * d / sqrt(d * d - r * r);
  vec3 position = centre + (right * corner.x + up * corner.y) * h;
  clip = u_view_projection * vec4(position, 1.0);
  return position;
}

// A quad over the screen's bounding rectangle of a box (its centre and three half axes,
// camera-relative m): corner `vertex` (0-5) returned camera-relative, with its clip position. The
// box's edges are clipped where they pass behind the camera; a box wholly behind it or off the
// screen is moved outside the clip volume.
vec3 box_screen_corner(vec3 centre, vec3 ax, vec3 ay, vec3 az, int vertex, out vec4 clip) {
  const vec2 corners[6] =
      vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec4 q[8];
  for (int k = 0; k < 8; ++k)
    q[k] =
        u_view_projection *
        vec4(centre + ((k & 1) != 0 ? ax : -ax) + ((k & 2) != 0 ? ay : -ay) + ((k & 4) != 0 ? az : -az), 1.0);
  // In front: w above a metre (the camera's near distance is far smaller than a cloud).
  const float near_w = 1.0;
  vec2 lo = vec2(3.4e38), hi = vec2(-3.4e38);
  for (int k = 0; k < 8; ++k) {
    if (q[k].w > near_w) lo = min(lo, q[k].xy / q[k].w), hi = max(hi, q[k].xy / q[k].w);
    for (int axis = 1; axis < 8; axis *= 2) {
      int m = k | axis;
      if (m == k || (q[k].w > near_w) == (q[m].w > near_w)) continue;
      // the edge where it crosses w = near_w
      vec4 x = mix(q[k], q[m], (near_w - q[k].w) / (q[m].w - q[k].w));
      lo = min(lo, x.xy / near_w), hi = max(hi, x.xy / near_w);
    }
  }
  if (any(greaterThan(lo, vec2(1.0))) || any(lessThan(hi, vec2(-1.0)))) {
    clip = vec4(2.0, 2.0, 2.0, 1.0);
    return vec3(0.0);
  }
  vec2 ndc = clamp(mix(lo, hi, corners[vertex] * 0.5 + 0.5), vec2(-1.0), vec2(1.0));
  clip = vec4(ndc, 0.5, 1.0);
  vec4 p = u_inverse_view_projection * clip;
  return p.xyz / p.w;
}
