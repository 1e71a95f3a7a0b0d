// Debug spheres and boxes without vertex buffers: positions generated from gl_VertexID.
uniform mat4 u_view_projection;
uniform vec3 u_center;  // camera-relative
uniform vec3 u_size;
uniform int u_shape;    // 0 sphere (a u_slices x u_slices / 2 grid of quads), 1 box
uniform int u_slices;
out vec3 v_normal;
out vec3 v_position;

// Vertex id of the sphere's (u_slices + 1) x (u_slices / 2 + 1) grid, drawn indexed (the seam's
// column twice).
vec3 sphere_vertex(int id, out vec3 n) {
  int slices = u_slices, stacks = u_slices / 2;
  int i = id % (slices + 1), j = id / (slices + 1);
  vec2 uv = vec2(i, j) / vec2(slices, stacks);
  float phi = uv.x * 6.28318531, theta = uv.y * 3.14159265;
  n = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), -cos(theta));
  return n * u_size.x;
}

vec3 box_vertex(int id, out vec3 n) {
  int face = id / 6, corner = id % 6;
  const vec2 q[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  int axis = face % 3;
  float s = face < 3 ? 1.0 : -1.0;
  vec3 p;
  vec2 c = q[corner] * vec2(s, 1.0);  // flip winding on the negative faces
  if (axis == 0) p = vec3(s, c.x, c.y);
  else if (axis == 1) p = vec3(c.y, s, c.x);
  else p = vec3(c.x, c.y, s);
  n = vec3(0.0);
  n[axis] = s;
  return p * u_size;
}

void main() {
  vec3 n;
  vec3 p = u_shape == 0 ? sphere_vertex(gl_VertexID, n) : box_vertex(gl_VertexID, n);
  v_normal = n;
  v_position = u_center + p;
  gl_Position = u_view_projection * vec4(v_position, 1.0);
}
