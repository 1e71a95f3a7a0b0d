// One puff of the mesh clusters, instanced in the sorted order. PUFF_PROXY_MESH 1: the proxy mesh
// (pulled by gl_VertexID) scaled to the puff's ellipsoid, which it encloses (drawn from its far
// side); 0: a quad facing the camera that covers the puff's bounding sphere (the whole screen when
// the camera is near it). A slot without a puff is moved outside the clip volume.
#include "clouds/clusters.glsl"
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(std430, binding = 5) readonly buffer ClusterOrder { uvec2 cp_order[]; };
#if PUFF_PROXY_MESH
layout(std430, binding = 6) readonly buffer PuffProxy { vec4 cp_proxy[]; };
#endif
uniform mat4 u_view_projection;          // camera-relative
uniform mat4 u_inverse_view_projection;
out vec3 v_position;                     // camera-relative m (along the pixel's ray)
flat out int v_puff;
flat out vec4 v_base_plane;              // up at the puff; w: the camera's height above the cluster's base (m)
uniform vec4 u_up_radius;                // up at the camera; w: the camera's distance from the planet's centre

void main() {
  int puff = int(cp_order[gl_InstanceID].y);
  v_puff = puff;
  // Only the centre and radii: software vertex processing pays for every load.
  vec4 centre = cp_puffs[puff].centre;
  vec3 radii = cp_puffs[puff].radii.xyz;
  vec3 up = normalize(u_up_radius.xyz * u_up_radius.w + centre.xyz);
  v_base_plane = vec4(up, cp_puffs[puff].sky.w - dot(centre.xyz, up));
  if (centre.w <= 0.0) {
    v_position = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
#if PUFF_PROXY_MESH
  vec3 unit = cp_proxy[gl_VertexID].xyz * radii;
  v_position = centre.xyz + unit.x * u_axis_wind + unit.y * u_axis_across + unit.z * u_axis_up;
  gl_Position = u_view_projection * vec4(v_position, 1.0);
#else
  const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 corner = corners[gl_VertexID];
  float r = max(radii.x, max(radii.y, radii.z)), d = length(centre.xyz);
  if (d < 2.0 * r) {
    // Near or inside it: every pixel is tried.
    gl_Position = vec4(corner, 0.5, 1.0);
    vec4 p = u_inverse_view_projection * vec4(corner, 0.5, 1.0);
    v_position = p.xyz / p.w;
  } else {
    // The cone of rays that touch the sphere is r d / sqrt(d^2 - r^2) wide at the centre's distance.
    vec3 forward = centre.xyz / d;
    vec3 right = normalize(cross(forward, abs(forward.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
    vec3 up = cross(right, forward);
    float h = r * d / sqrt(d * d - r * r);
    v_position = centre.xyz + (right * corner.x + up * corner.y) * h;
    gl_Position = u_view_projection * vec4(v_position, 1.0);
  }
#endif
}
