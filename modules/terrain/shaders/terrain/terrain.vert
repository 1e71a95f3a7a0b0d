// Terrain vertices: model space (z-up metres) -> camera-relative, bent onto the planet.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_view_projection;
uniform vec3 u_anchor_relative;  // model origin minus camera, computed in double on the CPU
uniform vec2 u_anchor_xy;        // model origin from the scene origin (where the planet touches the plane)
uniform mat3 u_rotation;
uniform float u_inverse_two_radius;  // 1 / (2 R); 0 keeps the model flat
out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  vec3 p = u_rotation * a_position;
  vec2 ground = u_anchor_xy + p.xy;
  // The sphere below the tangent plane at the scene origin: z drops by (x^2 + y^2) / 2R.
  p.z -= dot(ground, ground) * u_inverse_two_radius;
  v_position = u_anchor_relative + p;
  v_normal = u_rotation * a_normal;
  v_uv = a_uv;
  gl_Position = u_view_projection * vec4(v_position, 1.0);
}
