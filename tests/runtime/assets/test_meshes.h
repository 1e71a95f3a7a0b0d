#pragma once
// Meshes shared by the tests and the fuzz seed generator (no GoogleTest here).
#include <cmath>

#include "welkin/assets/glb_writer.h"

namespace welkin::assets::test {

// A (n+1) x (n+1) vertex grid in the XZ plane, 2 n^2 triangles, UVs over [0,1]^2.
inline MeshData grid_mesh(int n, float size = 10.0f) {
  MeshData m;
  m.name = "grid";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float u = float(i) / n, v = float(j) / n;
      m.positions.emplace_back((u - 0.5f) * size, 0.25f * std::sin(6.0f * u) * std::cos(5.0f * v),
                               (v - 0.5f) * size);
      m.normals.emplace_back(0.0f, 1.0f, 0.0f);
      m.uv0.emplace_back(u, v);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  return m;
}

}  // namespace welkin::assets::test
