#pragma once
// A texture magnified through a cubic B-spline: the far clouds (clusters and billboards) are drawn at
// a quarter of the frame, and bilinear reads magnified that much show each texel's square at their
// edges (stair steps). The B-spline's weights are positive and sum to one, so premultiplied colour
// stays valid (no ringing, unlike Catmull-Rom's). Four bilinear reads (Sigg and Hadwiger 2005).
vec4 clouds_b_spline(sampler2D s, vec2 uv) {
  vec2 size = vec2(textureSize(s, 0));
  vec2 texel = uv * size - 0.5;
  vec2 base = floor(texel), f = texel - base;
  vec2 w0 = (1.0 - f) * (1.0 - f) * (1.0 - f) / 6.0, w1 = (4.0 + f * f * (3.0 * f - 6.0)) / 6.0;
  vec2 w3 = f * f * f / 6.0, w2 = 1.0 - w0 - w1 - w3;
  vec2 g0 = w0 + w1, g1 = w2 + w3;
  // Each pair of taps merged into one bilinear read between them.
  vec2 p0 = (base - 0.5 + w1 / g0) / size, p1 = (base + 1.5 + w3 / g1) / size;
  return g0.y * (g0.x * textureLod(s, p0, 0.0) + g1.x * textureLod(s, vec2(p1.x, p0.y), 0.0)) +
         g1.y * (g0.x * textureLod(s, vec2(p0.x, p1.y), 0.0) + g1.x * textureLod(s, p1, 0.0));
}
