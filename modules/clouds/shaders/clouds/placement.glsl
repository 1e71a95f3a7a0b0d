#pragma once
// Placing things where a layer's weather holds cloud (the mesh clusters' puffs, the billboards): a
// grid of cells in the camera's tangent plane that drifts with the layer's wind, hashed per cell.
// Needs clouds/density.glsl.
uniform int u_grid;               // cells per side
uniform float u_cell_m;
uniform ivec2 u_first_cell;       // the global index (in the drifting grid) of cell (0, 0)
uniform vec2 u_first_corner;      // its corner, camera-relative (east, north) m
uniform vec3 u_east, u_north;     // the camera's tangent plane (camera-relative axes)
uniform uint u_seed;

// A point at altitude h above the surface at camera-relative (east, north): the planet's curvature
// taken exactly, written so that float keeps it to a metre at 100 km.
vec3 layer_point(vec2 en, float h) {
  float r_c = cl.camera_radius_m, R = cl.planet_radius_m + h, rho2 = dot(en, en);
  float z = ((h - cl.camera_altitude_m) * (R + r_c) - rho2) / (sqrt(max(R * R - rho2, 0.0)) + r_c);
  return en.x * u_east + en.y * u_north + z * cl.up;
}

// Hash (Jarzynski & Olano 2020, PCG) of a cell, an index and the seed into [0, 1)^4.
uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  return v;
}
vec4 random4(ivec2 cell, int index, uint salt) {
  return vec4(pcg4d(uvec4(uvec2(cell), uint(index), u_seed * 4u + salt)) >> 8u) / 16777216.0;
}

vec2 cell_centre_en(int cell) {
  return u_first_corner + (vec2(cell % u_grid, cell / u_grid) + 0.5) * u_cell_m;
}

// What a layer's weather allows (before the noise erodes it) around a cell's centre: summed over
// five columns at a third of the layer's height, the centre and four at half `radius` (m) from it.
float weather_score(CloudLayerGpu L, vec2 en, float radius) {
  const vec2 columns[5] =
      vec2[5](vec2(0.0), vec2(0.5, 0.0), vec2(-0.5, 0.0), vec2(0.0, 0.5), vec2(0.0, -0.5));
  float score = 0.0;
  for (int c = 0; c < 5; ++c) {
    vec3 x = layer_point(en + columns[c] * radius, L.base_m + L.thickness_m * 0.33);
    clouds_system_g = clouds_weather_system_at(x);
    clouds_painted_sample = 2.0;
    float t, d0;
    score += clouds_layer_envelope(L, clouds_weather_fetch(L, x), L.follows_map > 0.5, x, clouds_altitude(x),
                                   t, d0);
  }
  return score;
}
