#pragma once
// One texel of the clouds' shadow map: the optical depth toward the sun along its column as a curve
// of the distance from the cascade's start plane. Written by clouds/shadow_map.comp, read by
// clouds/light_term.glsl.
//
// The curve is kept by where it crosses a few optical depths (an inverse of the column's opacity),
// which places its knots where the light changes, whatever the column's length: the front (0), the
// depths 0.25, 1, 3 and 8, the back of the last cloud (the total). A single front and mean extinction
// (a beer shadow map) assumed one cloud a column: toward a sun 10 degrees up a column crosses 8 km of
// cumulus layer, several clouds and the gaps between them, and the mean extinction of them all, taken
// from the first cloud's front, put the lit top of a cloud further on in the dark (the direct beam
// there 1e-4 of the path tracer's, docs/clouds-light.md).
const float kCloudsShadowKnots[4] = float[4](0.25, 1.0, 3.0, 8.0);

struct CloudsShadowColumn {
  vec4 near;  // the front, and the distances at which the optical depth reaches 0.25, 1 and 3
  vec4 far;   // the distance at which it reaches 8, the back, the total, the decks' optical depth
};

// The optical depth between the column's start and `depth` along it: linear between the knots. A knot
// the column never reaches lies at the back; its depth is the total there.
float clouds_column_optical_depth(CloudsShadowColumn c, float depth) {
  float total = c.far.z;
  float d[6] = float[6](c.near.x, c.near.y, c.near.z, c.near.w, c.far.x, c.far.y);
  float tau[6] = float[6](0.0, min(kCloudsShadowKnots[0], total), min(kCloudsShadowKnots[1], total),
                          min(kCloudsShadowKnots[2], total), min(kCloudsShadowKnots[3], total), total);
  float sum = 0.0;
  for (int i = 1; i < 6; ++i)
    sum += (tau[i] - tau[i - 1]) * clamp((depth - d[i - 1]) / max(d[i] - d[i - 1], 1e-3), 0.0, 1.0);
  return sum;
}
