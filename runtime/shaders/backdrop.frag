#include "welkin/view.glsl"
in vec2 v_ndc;
out vec4 o_color;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_zenith, u_horizon, u_ground;
uniform int u_grid;
void main() {
  vec3 d = view_ray_direction(u_inverse_view_projection, v_ndc);
  vec3 c = d.z >= 0.0 ? mix(u_horizon, u_zenith, sqrt(d.z)) : u_ground;
  if (u_grid == 1) {
    float el = degrees(asin(clamp(d.z, -1.0, 1.0)));
    float az = degrees(atan(d.x, d.y));
    vec2 g = abs(fract(vec2(az, el) / 10.0 + 0.5) - 0.5) * 10.0;  // degrees to the nearest line
    vec2 w = fwidth(vec2(az, el));
    float line = 1.0 - min(1.0, min(g.x / max(w.x, 1e-4), g.y / max(w.y, 1e-4)));
    c *= 1.0 - 0.35 * line;
  }
  o_color = vec4(c, 1.0);
}
