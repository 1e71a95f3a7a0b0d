#pragma once
// A quad facing the camera that covers a sphere (six vertices, gl_VertexID 0-5): the cone of rays
// that touch it, at the centre's distance; the whole screen when the camera is near or inside it.
// Returns the corner camera-relative (m, on the pixel's ray) and its clip position.
uniform mat4 u_view_projection;  // camera-relative
uniform mat4 u_inverse_view_projection;

vec3 sprite_corner(vec3 centre, float r, int vertex, out vec4 clip) {
  const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
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
