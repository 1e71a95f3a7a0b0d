// Fills one of the clouds' tileable noise volumes (CLOUDS_NOISE selects which):
//   0 shape (128^3, RGBA8): r Perlin-Worley base eroded by three octaves of Worley fBm (Schneider
//     2015); gba are filled with the turbulence (3) afterwards (src/noise_volumes.cpp)
//   1 detail (32^3, R8): Worley fBm at higher frequencies
//   2 weather (64^3, RGBA8): r, g, b coverage signals for layers (layer i reads channel i % 3),
//     a the base variation; sampled at planet-centred positions, so the globe has no seams. The
//     coverage channels are equalised to a uniform distribution afterwards (src/noise_volumes.cpp).
//   3 turbulence (the shape's size, RGBA16F): xyz the curl of a tileable Perlin vector potential,
//     taken with central differences on the texel grid itself, so that the volume's own
//     central-difference divergence vanishes (the two difference operators commute); scaled so that
//     the longest vector has length 1 and packed into the shape's gba afterwards (src/noise_volumes.cpp).
//   4 weather systems (32^3, R8): two smooth octaves of Perlin noise over thousands of kilometres,
//     equalised afterwards.
#include "clouds/noise.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#if CLOUDS_NOISE == 3
layout(rgba16f, binding = 0) uniform writeonly image3D u_out;
#elif CLOUDS_NOISE == 0 || CLOUDS_NOISE == 2
layout(rgba8, binding = 0) uniform writeonly image3D u_out;
#else  // 1, 4
layout(r8, binding = 0) uniform writeonly image3D u_out;
#endif
uniform int u_size;
uniform uint u_seed;

#if CLOUDS_NOISE == 3
// One component of the vector potential at texel q (wrapped, so that every invocation that reads a
// texel computes the same bits for it).
float potential(ivec3 q, int component) {
  q = (q + u_size) % u_size;
  vec3 uvw = (vec3(q) + 0.5) / float(u_size);
  return clouds_perlin_fbm(uvw * 4.0, 4, u_seed + 7000u + uint(component) * 113u, 3) - 0.5;
}
#endif

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(id, ivec3(u_size)))) return;
  vec3 uvw = (vec3(id) + 0.5) / float(u_size);
#if CLOUDS_NOISE == 0
  float perlin = clouds_perlin_fbm(uvw * 4.0, 4, u_seed, 5);
  float worley = clouds_worley_fbm(uvw * 6.0, 6, u_seed + 1000u);
  float perlin_worley = clamp(clouds_remap(perlin, worley - 1.0, 1.0, 0.0, 1.0), 0.0, 1.0);
  float erosion = clouds_worley_fbm(uvw * 12.0, 12, u_seed + 2000u);
  float shape = clamp(clouds_remap(perlin_worley, erosion - 1.0, 1.0, 0.0, 1.0), 0.0, 1.0);
  imageStore(u_out, id, vec4(shape, 0.5, 0.5, 0.5));
#elif CLOUDS_NOISE == 1
  imageStore(u_out, id, vec4(clouds_worley_fbm(uvw * 4.0, 4, u_seed + 3000u)));
#elif CLOUDS_NOISE == 3
  const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
  vec3 curl =
      vec3(potential(id + ey, 2) - potential(id - ey, 2) - potential(id + ez, 1) + potential(id - ez, 1),
           potential(id + ez, 0) - potential(id - ez, 0) - potential(id + ex, 2) + potential(id - ex, 2),
           potential(id + ex, 1) - potential(id - ex, 1) - potential(id + ey, 0) + potential(id - ey, 0));
  imageStore(u_out, id, vec4(curl * 0.5, 0.0));
#elif CLOUDS_NOISE == 4
  imageStore(u_out, id, vec4(clouds_perlin_fbm(uvw * 2.0, 2, u_seed + 8000u, 2)));
#else
  vec4 w;
  for (int c = 0; c < 3; ++c) {
    float p = clouds_perlin_fbm(uvw * 4.0, 4, u_seed + 4000u + uint(c) * 97u, 4);
    float cell = clouds_worley(uvw * 8.0, 8, u_seed + 5000u + uint(c) * 89u);
    // Continuous (no clamping to a constant), so that equalisation leaves no lump at one value.
    w[c] = clamp(0.6 * p + 0.4 * cell, 0.0, 1.0);
  }
  w.a = clouds_perlin_fbm(uvw * 8.0, 8, u_seed + 6000u, 3);
  imageStore(u_out, id, w);
#endif
}
