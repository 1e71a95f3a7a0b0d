#pragma once
// Tileable noise for the cloud textures, deterministic from a seed: integer hashes (no sin()), so
// every GPU produces the same bits. Each function repeats with `period` lattice cells per side.
uint clouds_hash(uvec3 p, uint seed) {
  // Three rounds of a 32-bit integer mix (Jarzynski & Olano 2020, pcg3d), folded to one value.
  uvec3 v = p * 1664525u + 1013904223u + seed * 747796405u;
  v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
  return v.x ^ v.y ^ v.z;
}
vec3 clouds_hash3(ivec3 cell, int period, uint seed) {
  // GLSL leaves % undefined for negative operands (Worley's cells left of the origin): floor instead.
  uvec3 c = uvec3(cell - period * ivec3(floor(vec3(cell) / float(period))));
  uint h = clouds_hash(c, seed);
  return vec3(h & 1023u, (h >> 10) & 1023u, (h >> 20) & 1023u) / 1023.0;
}

// Gradient (Perlin) noise in [-1, 1]-ish with a quintic fade; x in lattice units.
float clouds_perlin(vec3 x, int period, uint seed) {
  ivec3 i = ivec3(floor(x));
  vec3 f = x - vec3(i);
  vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  float n[8];
  for (int k = 0; k < 8; ++k) {
    ivec3 o = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    vec3 g = normalize(clouds_hash3(i + o, period, seed) * 2.0 - 1.0 + 1e-6);
    n[k] = dot(g, f - vec3(o));
  }
  return mix(mix(mix(n[0], n[1], u.x), mix(n[2], n[3], u.x), u.y),
             mix(mix(n[4], n[5], u.x), mix(n[6], n[7], u.x), u.y), u.z);
}

// Inverted cellular (Worley) noise in [0, 1]: 1 at a feature point, 0 far from all.
float clouds_worley(vec3 x, int period, uint seed) {
  ivec3 i = ivec3(floor(x));
  vec3 f = x - vec3(i);
  float d = 1.0;
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int w = -1; w <= 1; ++w) {
        ivec3 o = ivec3(w, y, z);
        vec3 r = vec3(o) + clouds_hash3(i + o, period, seed) - f;
        d = min(d, dot(r, r));
      }
  return 1.0 - clamp(sqrt(d), 0.0, 1.0);
}

// Octaves of Perlin noise mapped to about [0, 1]; each doubles the frequency and keeps the tiling.
float clouds_perlin_fbm(vec3 x, int period, uint seed, int octaves) {
  float sum = 0.0, amplitude = 0.5, norm = 0.0;
  for (int k = 0; k < octaves; ++k) {
    sum += amplitude * clouds_perlin(x, period, seed + uint(k) * 131u);
    norm += amplitude;
    amplitude *= 0.5, x *= 2.0, period *= 2;
  }
  return clamp(sum / norm * 0.9 + 0.5, 0.0, 1.0);
}

// Schneider's Worley fBm: three octaves weighted 0.625, 0.25, 0.125.
float clouds_worley_fbm(vec3 x, int period, uint seed) {
  return clouds_worley(x, period, seed) * 0.625 + clouds_worley(x * 2.0, period * 2, seed + 17u) * 0.25 +
         clouds_worley(x * 4.0, period * 4, seed + 29u) * 0.125;
}

float clouds_remap(float v, float lo, float hi, float new_lo, float new_hi) {
  return new_lo + (v - lo) / (hi - lo) * (new_hi - new_lo);
}
