#pragma once
// Subdivision surfaces through OpenSubdiv: Loop for all-triangle meshes, Catmull-Clark otherwise.
// Uniform refinement (Far topology, Osd CPU stencil evaluation, projected to the limit surface) or,
// with an adaptive distance, a crack-free tessellation of the limit surface whose density falls
// with the distance to a camera point (OpenSubdiv Bfr), both under a triangle budget.
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace welkin::assets {

// Polygons given as vertex counts and a flat index list (3 = triangle, 4 = quad, more for CC).
struct ControlMesh {
  std::vector<glm::vec3> positions;
  std::vector<int> face_sizes;
  std::vector<int> face_indices;
};

enum class SubdivScheme { automatic, loop, catmull_clark };

struct RefineSettings {
  int levels = 2;                   // maximum refinement level (each level quarters faces)
  size_t max_triangles = 1u << 20;  // levels are lowered until the output fits
  glm::vec3 camera_position{0.0f};
  float adaptive_distance = 0.0f;                 // > 0: full level within it, one level less per doubling
  SubdivScheme scheme = SubdivScheme::automatic;  // automatic: Loop if all triangles, else CC
  bool limit_surface = true;                      // uniform mode: project vertices onto the limit surface
  bool sharp_boundary_corners = true;             // open meshes (terrain tiles) keep their corners
};

struct RefinedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // limit-surface normals (or averaged when not at limit)
  std::vector<uint32_t> indices;   // triangles
  SubdivScheme scheme = SubdivScheme::loop;
  int level = 0;  // level actually used (highest, in adaptive mode)
  bool adaptive = false;
  size_t triangle_count() const { return indices.size() / 3; }
};

// Throws welkin::Error for bad topology (index out of range, face with < 3 or repeated vertices,
// triangles given to Loop with quads) or when even level 0 exceeds the triangle budget.
RefinedMesh refine(const ControlMesh& mesh, const RefineSettings& settings);

// Uniform refinement counts per level without building geometry (level 0 = control mesh),
// as OpenSubdiv's Far topology refiner reports them: vertices and faces (quads for CC).
struct LevelCounts {
  int vertices = 0, faces = 0;
};
std::vector<LevelCounts> uniform_level_counts(const ControlMesh& mesh, SubdivScheme scheme, int levels);

}  // namespace welkin::assets
