// Bilinear splat of a star over the 2x2 pixels its point covers: the weights sum to 1 (stars.vert).
flat in vec3 v_radiance;
flat in vec2 v_center;
out vec4 o_color;

void main() {
  vec2 w = max(vec2(1.0) - abs(gl_FragCoord.xy - v_center), vec2(0.0));
  o_color = vec4(v_radiance * (w.x * w.y), 0.0);
}
