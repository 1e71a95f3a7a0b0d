// The sky's geometry. Without ATM_SKY_DISCS: one full-screen triangle at depth 0 (infinity in
// reversed Z), so the depth test, not the shader, keeps it off the geometry; v_dir from
// sky_direction.glsl.
// With ATM_SKY_DISCS: a small square of directions around the sun (instance 0) and the moon
// (instance 1) as points at infinity, so only the pixels near a disc run the disc code.
#include "atmosphere/common.glsl"
#ifndef ATM_SKY_MODE
#define ATM_SKY_MODE 0
#endif
#ifndef ATM_SKY_DISCS
#define ATM_SKY_DISCS 0
#endif
#ifndef ATM_SKY_GROUND_LIGHT
#define ATM_SKY_GROUND_LIGHT 0
#endif
#include "atmosphere/sky_direction.glsl"
out vec3 v_dir;
uniform float u_pixel_angle;

void main() {
#if ATM_SKY_DISCS
  bool sun = gl_InstanceID == 0;
  vec3 d = sun ? atm.sun_direction : atm.moon_direction;
  float radius = sun ? atm.sun_angular_radius_rad : atm.moon_angular_radius_rad;
  bool on = sun ? atm.sun_disc > 0.5 : atm.moon_disc > 0.5;
  // Two pixels of margin for the anti-aliased edge; half-angles beyond 80 degrees are not discs.
  float half_size = tan(min(radius + 2.0 * u_pixel_angle, radians(80.0)));
  vec3 t = normalize(cross(d, abs(d.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 b = cross(d, t);
  const vec2 corners[6] =
      vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  vec2 c = corners[gl_VertexID % 6];
  vec3 dir = d + (c.x * t + c.y * b) * half_size;
  v_dir = dir;
  gl_Position = on ? atm.view_projection * vec4(dir, 0.0) : vec4(0.0);
#else
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  v_dir = sky_direction(p);
  gl_Position = vec4(p, 0.0, 1.0);
#endif
}
