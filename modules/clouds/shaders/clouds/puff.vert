// One puff of the mesh clusters (a box, one column of its cell through the layer), instanced in the
// sorted order. PUFF_PROXY_MESH 1: the proxy mesh (pulled by gl_VertexID) scaled to enclose the box
// (drawn from its far side); 0: a quad over the box's screen rectangle (the whole screen when the
// camera is in it). A slot without a puff is moved outside the clip volume.
#include "clouds/clusters.glsl"
#include "clouds/sprite.glsl"
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(std430, binding = 5) readonly buffer ClusterOrder { uvec2 cp_order[]; };
#if PUFF_PROXY_MESH
layout(std430, binding = 6) readonly buffer PuffProxy { vec4 cp_proxy[]; };
#endif
out vec3 v_position;                     // camera-relative m (along the pixel's ray)
flat out int v_puff;
flat out vec3 v_up;  // the local vertical at the puff
// What the light needs of the puff, loaded here once per vertex rather than by every pixel.
flat out vec3 v_light, v_sky, v_ap_inscattering, v_ap_transmittance;
flat out float v_system_signal;  // the weather systems' signal at the puff
flat out vec4 v_light_gradient;  // how the depth toward the light changes across the box; w: at its centre
uniform vec4 u_up_radius;  // up at the camera; w: the camera's distance from the planet's centre

void main() {
  int puff = int(cp_order[gl_InstanceID].y);
  v_puff = puff;
  // Only the centre and radii: software vertex processing pays for every load.
  vec3 centre = cp_puffs[puff].centre, radii = cp_puffs[puff].radii;
  v_up = normalize(u_up_radius.xyz * u_up_radius.w + centre);
  v_light = cp_puffs[puff].light, v_sky = cp_puffs[puff].sky;
  v_system_signal = cp_puffs[puff].system_signal;
  v_ap_inscattering = cp_puffs[puff].ap_inscattering, v_ap_transmittance = cp_puffs[puff].ap_transmittance;
  v_light_gradient = vec4(cp_puffs[puff].light_depth_gradient, cp_puffs[puff].light_depth);
  if (cp_puffs[puff].extinction_per_density <= 0.0) {
    v_position = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
#if PUFF_PROXY_MESH
  // The proxy encloses the unit sphere, which sqrt(3) times encloses the unit cube.
  vec3 unit = cp_proxy[gl_VertexID].xyz * radii * 1.7320508;
  v_position = centre + unit.x * u_axis_wind + unit.y * u_axis_across + unit.z * u_axis_up;
  gl_Position = u_view_projection * vec4(v_position, 1.0);
#else
  v_position = box_screen_corner(centre, u_axis_wind * radii.x, u_axis_across * radii.y,
                                 u_axis_up * radii.z, gl_VertexID, gl_Position);
#endif
}
