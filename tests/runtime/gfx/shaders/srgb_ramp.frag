// Encodes a ramp of linear values (one per pixel along x, 0..1) with the tone map's sRGB encode, into
// an 8-bit target: what the CPU's exact transfer function must agree with.
#include "welkin/tonemap.glsl"
out vec4 o_color;
uniform int u_width;
void main() {
  float c = (gl_FragCoord.x - 0.5) / float(u_width - 1);
  o_color = vec4(linear_to_srgb(vec3(c)), 1.0);
}
