// One billboard, instanced in the sorted order: a quad over the screen's rectangle of the box that
// holds its cloud. Everything the same for all its pixels is found here once: its frame (along the wind,
// across it, up where it stands), the three views of the atlas around the direction it is seen from
// (their weights, and each view's plane and image axes as the pixel's ray meets them), and its light
// A slot without a cloud is moved outside the clip volume.
#include "clouds/billboards.glsl"
#include "clouds/sprite.glsl"
layout(std430, binding = 1) readonly buffer Billboards { Billboard bb_billboards[]; };
layout(std430, binding = 5) readonly buffer ClusterOrder { uvec2 bb_order[]; };
uniform vec4 u_up_radius;  // up at the camera; w: the camera's distance from the planet's centre
uniform vec3 u_axis_wind;  // the layer's wind direction (camera-relative)
out vec3 v_position;       // camera-relative m (along the pixel's ray)
flat out vec3 v_wind, v_across, v_up;
// Per view i: the plane (normal n, n . centre), and the texel coordinates of the point t along the
// ray: t (dir . a) + a.w and t (dir . b) + b.w; v_layers: each view's first atlas layer.
flat out vec4 v_plane[3], v_axis_a[3], v_axis_b[3];
flat out vec3 v_layers, v_weights;
flat out int v_billboard;  // its light and air are read where there is cloud (bb_billboards)
flat out float v_scale;    // its optical-depth scale

void main() {
  int billboard = int(bb_order[gl_InstanceID].y);
  Billboard b = bb_billboards[billboard];
  vec3 c = b.centre;
  v_billboard = billboard;
  v_scale = b.depth_scale;
  v_up = normalize(u_up_radius.xyz * u_up_radius.w + c);
  // The archetype's frame: the wind's direction where it stands, turned by its hash.
  vec3 wind = normalize(u_axis_wind - v_up * dot(u_axis_wind, v_up)), across = cross(v_up, wind);
  float turn = b.turn_rad;
  v_wind = cos(turn) * wind + sin(turn) * across;
  v_across = cross(v_up, v_wind);
  if (b.depth_scale <= 0.0) {
    v_position = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec3 toward_camera = -normalize(c);
  ivec3 views;
  billboard_views(vec3(dot(toward_camera, v_wind), dot(toward_camera, v_across), dot(toward_camera, v_up)),
                  views, v_weights);
  for (int i = 0; i < 3; ++i) {
    int v = views[i];
    vec3 d = billboard_view_direction(v / u_atlas.x, v % u_atlas.x), right, up;
    billboard_view_axes(d, right, up);
    vec3 n = d.x * v_wind + d.y * v_across + d.z * v_up;
    vec3 a = (right.x * v_wind + right.y * v_across + right.z * v_up) * (0.5 / u_box.z);
    vec3 e = (up.x * v_wind + up.y * v_across + up.z * v_up) * (0.5 / u_box.z);
    v_plane[i] = vec4(n, dot(c, n));
    v_axis_a[i] = vec4(a, 0.5 - dot(c, a));
    v_axis_b[i] = vec4(e, 0.5 - dot(c, e));
    v_layers[i] = float(2 * (int(b.archetype) * u_atlas.x * u_atlas.y + v));
  }
  // The box that holds the cloud (its window's cylinder), not its bounding sphere: a cloud seen from
  // the side covers a band, a third of the sphere's square.
  v_position = box_screen_corner(c, v_wind * (0.95 * u_box.x), v_across * (0.95 * u_box.x), v_up * u_box.y,
                                 gl_VertexID, gl_Position);
}
