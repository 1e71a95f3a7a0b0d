// Transmittance LUT: optical depth from (r, mu) to the top of the atmosphere. Samples crowd
// quadratically towards the ray's lowest point (its start for rising rays), where the air is
// densest: 40 steps then resolve a 1.2 km Mie scale height along a 100 km path.
#include "atmosphere/common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D o_lut;

// Midpoint rule over [0, len] with n steps, dense near t = 0; the ray is described from its
// densest point at radius r with zenith cosine mu, marching away from it.
vec3 optical_depth(float r, float mu, float len, int n) {
  AtmParams P = atm_params();
  vec3 depth = vec3(0.0);
  for (int i = 0; i < n; ++i) {
    float a = float(i) / float(n), b = float(i + 1) / float(n);
    float ta = len * a * a, tb = len * b * b;
    float t = 0.5 * (ta + tb);
    // Radius along the ray as a sum of non-negative terms where it matters (no cancellation).
    float ri = sqrt(max(0.0, r * r + t * (t + 2.0 * r * mu)));
    depth += atm_medium(P, ri - P.bottom).extinction * (tb - ta);
  }
  return depth;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(atm.transmittance_width, atm.transmittance_height);
  if (any(greaterThanEqual(texel, size))) return;
  vec2 r_mu = atm_transmittance_r_mu((vec2(texel) + 0.5) / vec2(size));
  float r = r_mu.x, mu = r_mu.y;
  float len = atm_distance_to_top(r, mu);
  int steps = atm.transmittance_steps;
  vec3 depth;
  float t_low = -r * mu;  // distance to the lowest point of a descending ray
  if (mu >= 0.0 || steps < 2) {
    depth = optical_depth(r, mu, len, steps);
  } else {
    // Both halves start at the lowest point: radius r_low, horizontal there (mu = 0).
    float r_low = r * sqrt(max(0.0, 1.0 - mu * mu));
    int n_down = clamp(int(round(float(steps) * t_low / len)), 1, steps - 1);
    depth = optical_depth(r_low, 0.0, t_low, n_down) + optical_depth(r_low, 0.0, len - t_low, steps - n_down);
  }
  imageStore(o_lut, texel, vec4(exp(-depth), 1.0));
}
