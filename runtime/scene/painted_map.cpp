#include "welkin/scene/painted_map.h"

#include <algorithm>
#include <cmath>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/image.h"
#include "welkin/scene/shared_state.h"

namespace welkin {

uint8_t PaintedMap::maximum() const {
  return texels.empty() ? 0 : *std::max_element(texels.begin(), texels.end());
}

glm::dmat3 MapFrame::axes() const {
  const glm::dvec3 up = glm::normalize(-planet_center_m);
  glm::dvec3 east = glm::dvec3(1, 0, 0) - up.x * up;
  if (glm::length(east) < 1e-6) east = glm::dvec3(0, 1, 0) - up.y * up;
  east = glm::normalize(east);
  return glm::dmat3(east, glm::cross(up, east), up);
}

glm::dvec2 MapFrame::uv(const glm::dvec3& world_m) const {
  const glm::dvec3 local = glm::transpose(axes()) * (world_m - planet_center_m);
  if (local.z <= 0.0) return {-1.0, -1.0};  // the far side of the planet
  const glm::dvec2 plane = glm::dvec2(local) * (planet_radius_m / local.z);
  return {plane.x / size_m + 0.5, 0.5 - plane.y / size_m};
}

glm::dvec3 MapFrame::ground_point(const glm::dvec2& uv) const {
  const glm::dvec3 local((uv.x - 0.5) * size_m, (0.5 - uv.y) * size_m, planet_radius_m);
  return planet_center_m + glm::normalize(axes() * local) * planet_radius_m;
}

MapFrame scene_map_frame(World& world, double size_m) {
  MapFrame f{.size_m = size_m};
  if (const PlanetFrame* planet = world.find_resource<PlanetFrame>(); planet && planet->from_scene) {
    f.planet_center_m = planet->center_m;
    f.planet_radius_m = planet->radius_m;
  }
  return f;
}

const PaintedMap& PaintedMaps::get(const std::string& file) {
  if (auto it = maps_.find(file); it != maps_.end()) return it->second;
  const ImageU8 image = read_png(file, kMaxPaintedMapSide);  // the side checked before decoding
  if (image.width != image.height || image.width > kMaxPaintedMapSide)
    throw Error(ErrorInfo{
        .file = file,
        .expected = "a square map of at most " + std::to_string(kMaxPaintedMapSide) + " texels a side",
        .found = std::to_string(image.width) + " x " + std::to_string(image.height)});
  PaintedMap map;
  map.side = image.width;
  map.texels.resize(size_t(map.side) * size_t(map.side));
  for (size_t i = 0; i < map.texels.size(); ++i) map.texels[i] = image.rgba[i * 4];
  map.revision = 1;
  return maps_[file] = std::move(map);
}

PaintedMap& PaintedMaps::edit(const std::string& file) {
  get(file);
  return maps_[file];
}

PaintedMap& PaintedMaps::create(const std::string& file, int side) {
  if (side < 1 || side > kMaxPaintedMapSide)
    throw Error(ErrorInfo{.file = file,
                          .expected = "1 to " + std::to_string(kMaxPaintedMapSide) + " texels a side",
                          .found = std::to_string(side)});
  PaintedMap& map = maps_[file];
  const uint64_t revision = map.revision;
  map = PaintedMap{.side = side,
                   .texels = std::vector<uint8_t>(size_t(side) * size_t(side), kPaintedMapNeutral)};
  map.revision = revision + 1;
  map.unsaved = true;
  return map;
}

void PaintedMaps::touched(PaintedMap& map) {
  ++map.revision;
  map.unsaved = true;
}

void PaintedMaps::save(const std::string& file) {
  PaintedMap& map = edit(file);
  ImageU8 image{map.side, map.side, std::vector<uint8_t>(map.texels.size() * 4)};
  for (size_t i = 0; i < map.texels.size(); ++i) {
    std::fill_n(&image.rgba[i * 4], 3, map.texels[i]);
    image.rgba[i * 4 + 3] = 255;
  }
  write_png(file, image);
  map.unsaved = false;
}

void PaintedMaps::save_unsaved() {
  for (auto& [file, map] : maps_)
    if (map.unsaved) save(file);
}

MapRegion copy_region(const PaintedMap& map, int x, int y, int width, int height) {
  MapRegion r{x, y, width, height, {}};
  r.texels.reserve(size_t(std::max(width, 0)) * size_t(std::max(height, 0)));
  for (int j = y; j < y + height; ++j)
    for (int i = x; i < x + width; ++i) r.texels.push_back(map.at(i, j));
  return r;
}

namespace {
// Copies r into the texels of a rectangle at (x0, y0) of width x height.
void paste_into(std::vector<uint8_t>& texels, int x0, int y0, int width, int height, const MapRegion& r) {
  if (r.x < x0 || r.y < y0 || r.width < 0 || r.height < 0 || r.x + r.width > x0 + width ||
      r.y + r.height > y0 + height || r.texels.size() != size_t(r.width) * size_t(r.height))
    throw Error(ErrorInfo{.message = "a map region that does not fit where it is pasted"});
  for (int j = 0; j < r.height; ++j)
    std::copy_n(&r.texels[size_t(j) * size_t(r.width)], r.width,
                &texels[size_t(r.y - y0 + j) * size_t(width) + size_t(r.x - x0)]);
}
}  // namespace

void paste_region(PaintedMap& map, const MapRegion& r) {
  paste_into(map.texels, 0, 0, map.side, map.side, r);
}
void paste_region(MapRegion& into, const MapRegion& r) {
  paste_into(into.texels, into.x, into.y, into.width, into.height, r);
}

MapRegion brush_bounds(const PaintedMap& map, const BrushStamp& s) {
  const int x0 = std::max(0, int(std::floor(s.cx - s.radius_texels))),
            x1 = std::min(map.side, int(std::ceil(s.cx + s.radius_texels)));
  const int y0 = std::max(0, int(std::floor(s.cy - s.radius_texels))),
            y1 = std::min(map.side, int(std::ceil(s.cy + s.radius_texels)));
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0, {}};
}

void apply_brush(PaintedMap& map, const BrushStamp& s) {
  const MapRegion b = brush_bounds(map, s);
  const double strength = std::clamp(s.strength, 0.0, 1.0);
  for (int j = b.y; j < b.y + b.height; ++j)
    for (int i = b.x; i < b.x + b.width; ++i) {
      const double d = std::hypot(i + 0.5 - s.cx, j + 0.5 - s.cy) / std::max(s.radius_texels, 1e-9);
      if (d >= 1.0) continue;
      const double falloff = 1.0 - d * d * (3.0 - 2.0 * d);  // smooth to zero at the rim
      uint8_t& t = map.texels[size_t(j) * size_t(map.side) + size_t(i)];
      t = uint8_t(std::lround(t + (double(s.target) - t) * strength * falloff));
    }
}

}  // namespace welkin
