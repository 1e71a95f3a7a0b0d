#include "welkin/shading.glsl"
in vec3 v_normal;
in vec3 v_position;
out vec4 o_color;
uniform vec3 u_albedo;
void main() {
  o_color = vec4(shade_lambert(u_albedo, normalize(v_normal), v_position), 1.0);
}
