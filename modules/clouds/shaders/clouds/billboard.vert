// One billboard, instanced in the sorted order: a quad facing the camera over its box's bounding
// sphere; its frame (along the wind, across it, up where it stands) and the four views of the atlas
// around the direction it is seen from, with their weights. A slot without a cloud is moved outside
// the clip volume.
#include "clouds/billboards.glsl"
#include "clouds/sprite.glsl"
layout(std430, binding = 1) readonly buffer Billboards { Billboard bb_billboards[]; };
layout(std430, binding = 5) readonly buffer ClusterOrder { uvec2 bb_order[]; };
uniform vec4 u_up_radius;  // up at the camera; w: the camera's distance from the planet's centre
uniform vec3 u_axis_wind;  // the layer's wind direction (camera-relative)
out vec3 v_position;       // camera-relative m (along the pixel's ray)
flat out int v_billboard;
flat out vec3 v_wind, v_across, v_up;
flat out ivec4 v_views;
flat out vec4 v_weights;

void main() {
  int billboard = int(bb_order[gl_InstanceID].y);
  v_billboard = billboard;
  vec4 centre = bb_billboards[billboard].centre;
  v_up = normalize(u_up_radius.xyz * u_up_radius.w + centre.xyz);
  v_wind = normalize(u_axis_wind - v_up * dot(u_axis_wind, v_up));
  v_across = cross(v_up, v_wind);
  vec3 toward_camera = -normalize(centre.xyz);
  billboard_views(vec3(dot(toward_camera, v_wind), dot(toward_camera, v_across), dot(toward_camera, v_up)), v_views, v_weights);
  if (centre.w <= 0.0) {
    v_position = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  v_position = sprite_corner(centre.xyz, u_box.z, gl_VertexID, gl_Position);
}
