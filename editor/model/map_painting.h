#pragma once
// Painting a map a module declares (model/module_panels.h): where its component's map lies on the
// planet, making a new one beside the scene, and brush stamps at world points, each an undoable
// edit of the document. Shared by the map panel, the viewport's brush and scripts.
#include <functional>
#include <optional>
#include <string>

#include "model/editor_document.h"
#include "model/module_panels.h"
#include "welkin/scene/painted_map.h"

namespace welkin::editor {

enum class BrushMode { add, clear, reset };  // toward 255, 0 and the neutral 128
struct MapBrush {
  double radius_m = 3000.0;
  double strength = 0.5;
  BrushMode mode = BrushMode::add;
};

// The map a module declares at COMPONENT/FIELD (a "map" panel in its editor/panels.json); throws Error.
MapFieldSpec declared_map(EditorDocument& doc, const std::string& component_field);
// "add", "clear" or "reset"; throws Error.
BrushMode brush_mode_named(const std::string& word);

// The component holding a map: its entity, its file (empty: none yet) and where the map lies.
struct MapTarget {
  EntityId entity = kNoEntity;
  std::string file;
  MapFrame frame;
};
// Throws Error when no entity has the component or a field is not what the spec says.
MapTarget find_map(EditorDocument& doc, const MapFieldSpec& spec);

// The file a new map of a saved scene gets beside the scene: <scene stem>.<file field>.png, or with
// -2, -3, ... before .png, the first name for which `taken` is false (at most kMaxNewMapNames tried).
inline constexpr int kMaxNewMapNames = 1000;
std::string new_map_file(const std::string& scene_path, const MapFieldSpec& spec,
                         const std::function<bool(const std::string&)>& taken);
// Names a new map in the component (one undoable edit): a neutral map of `side` texels, written at
// once under a name no file, held map, value of the scene or of its history has yet, so the field
// always changes and undoing or redoing never finds a map where there was none. No file is ever
// replaced. Throws Error when the scene has not been saved yet (the map has no place) or `side` is
// out of range.
std::string new_map(EditorDocument& doc, const MapFieldSpec& spec, int side);

// One stamp at a world point (the map is read along the planet's radius, so any altitude serves).
// False when the stamp misses the map. `continuous`: part of a stroke (one undo step).
bool paint_at(EditorDocument& doc, const MapFieldSpec& spec, const glm::dvec3& world_m, const MapBrush& brush,
              bool continuous = false);

// Where a ray from `origin_m` meets the sphere `altitude_m` above the planet (the first crossing
// ahead); nothing when it misses.
std::optional<glm::dvec3> ray_at_altitude(const MapFrame& frame, const glm::dvec3& origin_m, const glm::dvec3& direction,
                                          double altitude_m);

}  // namespace welkin::editor
