#pragma once
// A terrain (or any static glTF scenery) placed on the planet. Its file is loaded once per world,
// split into chunks with simplified levels of detail, and drawn with metallic-roughness PBR.
#include <glm/glm.hpp>
#include <string>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin::terrain {

enum class Anchor : int { scene_origin = 0, offset = 1, geodetic = 2 };

struct Terrain {
  static constexpr std::string_view kTypeName = "terrain.Terrain";
  std::string file;                 // .glb or .gltf; glTF is y-up, the scene z-up (x = X, y = -Z, z = Y)
  Anchor anchor = Anchor::scene_origin;
  glm::dvec3 offset_m{0.0};         // anchor = offset: where the model's origin sits in the scene
  double latitude_deg = 0.0;        // anchor = geodetic: placed relative to timeofday.TimeOfDay's origin
  double longitude_deg = 0.0;
  float height_m = 0.0f;            // height of the model's origin above the scene origin's ground
  float heading_deg = 0.0f;         // rotation about up, clockwise from north
  bool follow_curvature = true;     // bend onto the planet (x^2+y^2)/2R below the tangent plane
  float planet_radius_km = 6360.0f; // used when the scene has no atmosphere to take it from
  int chunks_per_side = 16;         // spatial chunks for culling and level of detail
  int lod_levels = 4;               // each level about a quarter of the triangles of the one before
  float lod_pixel_error = 1.5f;     // a coarser level is used while its error stays under this many pixels
  bool compress_images = true;      // BC1 on the GPU (1/8 of RGBA8's memory, alpha dropped), kept on disk
  bool cast_shadows = true;         // cascaded shadow maps from the sun
  int shadow_map_size = 1024;       // per cascade (three cascades)
  float shadow_distance_m = 30000.0f;  // beyond it the terrain is unshadowed
  bool refine = false;              // OpenSubdiv refinement at load (Loop/Catmull-Clark)
  int refine_levels = 1;
  int refine_max_triangles = 4000000;
};
void describe(TypeBuilder<Terrain>& t);

}  // namespace welkin::terrain
