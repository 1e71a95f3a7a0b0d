#pragma once
// Maps painted over the planet (cloud coverage, ...): a square of 8-bit texels centred on the ground
// below the scene's origin, kept in a PNG file beside the scene. A module reads a map, the editor
// paints it; both go through the world's PaintedMaps, so a module sees every stroke as it is made and
// neither reaches into the other.
//
// Texel (0, 0) is the north-west corner (an image's top-left, as on a map). A point is placed on the
// map by projecting it along the planet's radius onto the tangent plane at the origin's ground point:
// a column of air stays on one texel at every altitude, and the map has no seams.
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

namespace welkin {

// The largest map side a scene may use (16 MiB of texels); checked from the file's header.
inline constexpr int kMaxPaintedMapSide = 4096;
// The value that changes nothing (a map a module adds 2 (v - 0.5) of something with).
inline constexpr uint8_t kPaintedMapNeutral = 128;

struct PaintedMap {
  int side = 0;                  // texels per side
  std::vector<uint8_t> texels;   // side x side, rows from north to south
  uint64_t revision = 0;         // bumped by every change, so readers know when to upload again
  bool unsaved = false;          // changed since read or written

  uint8_t at(int x, int y) const { return texels[size_t(y) * size_t(side) + size_t(x)]; }
  uint8_t maximum() const;
};

// Where a map lies on the planet: the tangent frame at the origin's ground point.
struct MapFrame {
  glm::dvec3 planet_center_m{0.0, 0.0, -6360000.0};
  double planet_radius_m = 6360000.0;
  double size_m = 100000.0;  // side of the square the map covers

  // East, north and up at the origin's ground point (the scene's x, y, z for a planet below it).
  glm::dmat3 axes() const;
  // A world point's place on the map in [0, 1]^2 (x east, y south, as texels run); outside: not on it.
  glm::dvec2 uv(const glm::dvec3& world_m) const;
  // The world point on the ground (altitude 0) at a map place.
  glm::dvec3 ground_point(const glm::dvec2& uv) const;
};

class World;
// A scene's map frame: the planet of the shared PlanetFrame (the atmosphere's when the scene has
// one), else Earth's 6360 km below the origin.
MapFrame scene_map_frame(World& world, double size_m);

// The maps of one world, keyed by the file name the scene gives.
class PaintedMaps {
 public:
  static constexpr std::string_view kTypeName = "core.PaintedMaps";

  // The map in `file`, read on first use (a square PNG of at most kMaxPaintedMapSide, its red channel).
  // Throws Error naming the file.
  const PaintedMap& get(const std::string& file);
  // The same map for changing (the editor); mark it changed with touched().
  PaintedMap& edit(const std::string& file);
  // A new map of `side` texels, all neutral, not yet written (it replaces one held under that name).
  PaintedMap& create(const std::string& file, int side);
  bool holds(const std::string& file) const { return maps_.count(file) != 0; }
  // Records a change made through edit().
  static void touched(PaintedMap& map);
  // Writes every map changed since it was read or written (atomically, as grey PNG).
  void save_unsaved();
  void save(const std::string& file);

 private:
  std::map<std::string, PaintedMap> maps_;
};

// One rectangle of a map's texels (an undo step of a brush stroke holds two of these).
struct MapRegion {
  int x = 0, y = 0, width = 0, height = 0;
  std::vector<uint8_t> texels;  // width x height, rows from north to south
};
MapRegion copy_region(const PaintedMap& map, int x, int y, int width, int height);
void paste_region(PaintedMap& map, const MapRegion& region);
// The same into a larger region (a stroke's record growing to cover a new stamp).
void paste_region(MapRegion& into, const MapRegion& region);

// A round brush: moves texels within radius_texels of (cx, cy) toward `target` by `strength` (0..1)
// times a smooth falloff. Returns the rectangle it may have changed (empty when off the map).
struct BrushStamp {
  double cx = 0.0, cy = 0.0;     // centre in texels (texel i spans [i, i + 1))
  double radius_texels = 4.0;
  double strength = 0.5;
  uint8_t target = 255;
};
MapRegion brush_bounds(const PaintedMap& map, const BrushStamp& stamp);
void apply_brush(PaintedMap& map, const BrushStamp& stamp);

}  // namespace welkin
