// One puff of the mesh clusters: the proxy mesh (pulled by gl_VertexID) scaled to the puff's
// ellipsoid, which it encloses; instances are drawn in the sorted order. A slot without a puff is
// moved outside the clip volume.
#include "clouds/clusters.glsl"
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(std430, binding = 5) readonly buffer ClusterOrder { uvec2 cp_order[]; };
layout(std430, binding = 6) readonly buffer PuffProxy { vec4 cp_proxy[]; };
uniform mat4 u_view_projection;  // camera-relative
out vec3 v_position;             // camera-relative m
flat out int v_puff;

void main() {
  int puff = int(cp_order[gl_InstanceID].y);
  ClusterPuff p = cp_puffs[puff];
  v_puff = puff;
  if (p.centre.w <= 0.0) {
    v_position = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec3 unit = cp_proxy[gl_VertexID].xyz * p.radii.xyz;
  v_position = p.centre.xyz + unit.x * u_axis_wind + unit.y * u_axis_across + unit.z * u_axis_up;
  gl_Position = u_view_projection * vec4(v_position, 1.0);
}
