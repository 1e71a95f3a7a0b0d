#pragma once
// Tone-mapping curves. Input: exposed scene-referred linear Rec.709; output: display linear [0,1].

// ACES fitted (Stephen Hill's fit of the RRT+ODT, sRGB monitor).
vec3 tonemap_aces(vec3 c) {
  const mat3 aces_in = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
  const mat3 aces_out =
      mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
  c = aces_in * c;
  vec3 a = c * (c + 0.0245786) - 0.000090537;
  vec3 b = c * (0.983729 * c + 0.4329510) + 0.238081;
  return clamp(aces_out * (a / b), 0.0, 1.0);
}

// AgX (Troy Sobotka) with the polynomial fit of its default contrast curve.
vec3 agx_contrast(vec3 x) {
  vec3 x2 = x * x, x4 = x2 * x2;
  return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}
vec3 tonemap_agx(vec3 c) {
  const mat3 agx_in = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                           0.0784335999999992, 0.878468636469772, 0.0784336,
                           0.0792237451477643, 0.0791661274605434, 0.879142973793104);
  const mat3 agx_out = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                            -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                            -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
  const float min_ev = -12.47393, max_ev = 4.026069;
  c = agx_in * max(c, vec3(1e-10));
  c = clamp((log2(c) - min_ev) / (max_ev - min_ev), 0.0, 1.0);
  c = agx_contrast(c);
  // The curve's output is display-encoded; return linear so one sRGB encode serves every curve.
  return clamp(pow(max(agx_out * c, vec3(0.0)), vec3(2.2)), 0.0, 1.0);
}

// The sRGB curve's power segment as a fit in square roots (Taylor's, within 0.0015 of 1.055 c^(1/2.4)
// - 0.055 over [0.0031308, 1]: under half an 8-bit step): llvmpipe evaluates pow as exp2(log2) per
// channel, a third of the cost of tone mapping a frame; three square roots are native instructions.
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
  vec3 curve = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c;
  return mix(12.92 * c, curve, step(vec3(0.0031308), c));
}
