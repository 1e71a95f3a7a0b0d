// libFuzzer target over OpenSubdiv refinement: the bytes become a control mesh (face sizes and
// indices, in range or not), the scheme, the level and the triangle budget, uniform or adaptive.
// Only welkin::Error may come out; what comes back must index its own vertices.
//
// Layout: [flags] [levels] [vertex count] [budget] [distance] then faces, each a size byte and that
// many index bytes. flags bit 0-1 scheme, 2 limit surface, 3 sharp corners, 4 raw float positions
// (NaN and infinity included) taken from the bytes after the header, 5 level counts instead.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "welkin/assets/subdivision.h"
#include "welkin/core/error.h"

using namespace welkin::assets;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 5) return 0;
  const uint8_t flags = data[0];
  RefineSettings s;
  s.scheme = SubdivScheme(flags & 3 ? (flags & 3) - 1 : 0);
  s.limit_surface = flags & 4;
  s.sharp_boundary_corners = flags & 8;
  s.levels = int8_t(data[1]);                     // negative and over 10 included
  const int vertices = 1 + data[2] % 96;          // small meshes: each run stays fast
  s.max_triangles = size_t(1) << (data[3] % 17);  // up to 64 Ki triangles
  if (data[4]) {                                  // adaptive: a distance, the camera at the origin
    s.adaptive_distance = float(data[4]) / 16.0f;
    s.camera_position = {float(data[4] % 7), 0.0f, 1.0f};
  }
  size_t at = 5;
  ControlMesh m;
  for (int i = 0; i < vertices; ++i) {
    glm::vec3 p(float(i % 10), float(i / 10), 0.0f);  // a grid, lifted by the bytes below
    if ((flags & 16) && at + sizeof(float) * 3 <= size) {
      std::memcpy(&p, data + at, sizeof(float) * 3);
      at += sizeof(float) * 3;
    } else if (at < size) {
      p.z = float(int8_t(data[at++])) / 32.0f;
    }
    m.positions.push_back(p);
  }
  while (at < size) {
    const int n = data[at++] % 10;  // 0..9: sizes below 3 are errors
    m.face_sizes.push_back(n);
    for (int k = 0; k < n && at < size; ++k)
      m.face_indices.push_back(int(int8_t(data[at++])) % (vertices + 2));  // some out of range
  }
  try {
    if (flags & 32) {
      const auto counts = uniform_level_counts(m, s.scheme, s.levels % 4);
      if (counts.empty()) std::abort();
      return 0;
    }
    const RefinedMesh r = refine(m, s);
    if (r.triangle_count() > s.max_triangles || r.indices.size() % 3) std::abort();
    if (!r.normals.empty() && r.normals.size() != r.positions.size()) std::abort();
    for (uint32_t i : r.indices)
      if (i >= r.positions.size()) std::abort();
  } catch (const welkin::Error&) {
  }
  return 0;
}
