// An exactly representable pattern: every channel is k/255.
vec4 pattern(ivec2 p) {
  return vec4(float((p.x * 7 + p.y) & 255), float((p.y * 13) & 255), float((p.x ^ p.y) & 255), float(PATTERN_ALPHA)) / 255.0;
}
