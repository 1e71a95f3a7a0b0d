#include "model/map_painting.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "welkin/core/error.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

MapFieldSpec declared_map(EditorDocument& doc, const std::string& component_field) {
  std::vector<std::string> errors;
  for (const ModulePanelSpec& p : read_module_panels(doc.world().modules(), errors))
    if (p.map && p.map->component + "/" + p.map->file_field == component_field) return *p.map;
  throw Error(ErrorInfo{.path = component_field, .message = "no module declares a painted map there (a \"map\" panel in its editor/panels.json)"});
}

BrushMode brush_mode_named(const std::string& word) {
  if (word == "add") return BrushMode::add;
  if (word == "clear") return BrushMode::clear;
  if (word == "reset") return BrushMode::reset;
  throw Error(ErrorInfo{.expected = "a brush mode add, clear or reset", .found = "'" + word + "'"});
}

MapTarget find_map(EditorDocument& doc, const MapFieldSpec& spec) {
  doc.require_component(spec.component);
  MapTarget t;
  t.entity = doc.entity_with(spec.component);
  if (t.entity == kNoEntity)
    throw Error(ErrorInfo{.path = spec.component, .message = "no entity has a " + spec.component + " component"});
  const nlohmann::json file = doc.get_field(t.entity, spec.component, spec.file_field);
  const nlohmann::json size = doc.get_field(t.entity, spec.component, spec.size_field);
  if (!file.is_string())
    throw Error(ErrorInfo{.path = spec.component + "/" + spec.file_field, .expected = "a file name", .found = file.dump()});
  if (!size.is_number() || !(size.get<double>() > 0.0))
    throw Error(ErrorInfo{.path = spec.component + "/" + spec.size_field, .expected = "a size in metres", .found = size.dump()});
  t.file = file.get<std::string>();
  t.frame = scene_map_frame(doc.world(), size.get<double>());
  return t;
}

std::string new_map_file(const std::string& scene_path, const MapFieldSpec& spec,
                         const std::function<bool(const std::string&)>& taken) {
  const std::filesystem::path scene(scene_path);
  const std::string stem = (scene.parent_path() / (scene.stem().string() + "." + spec.file_field)).string();
  for (int n = 1; n <= kMaxNewMapNames; ++n) {
    const std::string file = stem + (n == 1 ? "" : "-" + std::to_string(n)) + ".png";
    if (!taken(file)) return file;
  }
  throw Error(ErrorInfo{.file = stem + ".png", .message = "no free name for a new map beside the scene (" +
                                                          std::to_string(kMaxNewMapNames) + " tried)"});
}

namespace {
// Every string the history's values hold: each name any state of the document gave a field.
void collect_strings(const nlohmann::json& value, std::set<std::string>& out) {
  if (value.is_string())
    out.insert(value.get<std::string>());
  else if (value.is_structured())
    for (const nlohmann::json& v : value) collect_strings(v, out);
}
}  // namespace

std::string new_map(EditorDocument& doc, const MapFieldSpec& spec, int side) {
  const MapTarget target = find_map(doc, spec);
  if (doc.scene_path().empty())
    throw Error(ErrorInfo{.path = spec.component + "/" + spec.file_field,
                          .message = "save the scene first: a new map is written beside it"});
  PaintedMaps& maps = doc.world().resource<PaintedMaps>();
  // A name the scene holds now (this field's would make no edit to undo; another's would find a map
  // it did not have) or held at some step of the history (a map there when that step is undone to).
  std::set<std::string> named;
  collect_strings(save_scene(doc.world()), named);
  for (const HistoryStep& step : doc.history().steps())
    for (const Edit& edit : step.edits) collect_strings(edit.before, named), collect_strings(edit.after, named);
  const std::string file = new_map_file(doc.scene_path(), spec, [&](const std::string& name) {
    std::error_code ec;
    return named.count(name) || maps.holds(name) || std::filesystem::exists(name, ec) || ec;
  });
  // Written at once, neutral: an autosave (which holds no texels) or a crash must never leave a
  // scene naming a map file that does not exist.
  maps.create(file, side);
  maps.save(file);
  doc.set_field(target.entity, spec.component, spec.file_field, file);
  return file;
}

bool paint_at(EditorDocument& doc, const MapFieldSpec& spec, const glm::dvec3& world_m, const MapBrush& brush, bool continuous) {
  const MapTarget target = find_map(doc, spec);
  if (target.file.empty())
    throw Error(ErrorInfo{.path = spec.component + "/" + spec.file_field, .message = "there is no map to paint yet (make a new one)"});
  const glm::dvec2 uv = target.frame.uv(world_m);
  if (uv.x < 0.0 || uv.y < 0.0 || uv.x > 1.0 || uv.y > 1.0) return false;
  const int side = doc.world().resource<PaintedMaps>().get(target.file).side;
  BrushStamp stamp;
  stamp.cx = uv.x * side;
  stamp.cy = uv.y * side;
  // At most the whole map: the work and the undo record stay bounded by its size.
  stamp.radius_texels = std::clamp(brush.radius_m / target.frame.size_m * side, 0.5, double(side));
  stamp.strength = std::clamp(brush.strength, 0.0, 1.0);
  stamp.target = brush.mode == BrushMode::add ? 255 : brush.mode == BrushMode::clear ? 0 : kPaintedMapNeutral;
  return doc.paint_map(target.file, stamp, continuous);
}

std::optional<glm::dvec3> ray_at_altitude(const MapFrame& frame, const glm::dvec3& origin_m, const glm::dvec3& direction,
                                          double altitude_m) {
  const glm::dvec3 d = glm::normalize(direction), o = origin_m - frame.planet_center_m;
  const double r = frame.planet_radius_m + altitude_m;
  // |o + t d|^2 = r^2, with c = |o|^2 - r^2 formed as a product so that it keeps its precision.
  const double b = glm::dot(o, d), c = (glm::length(o) - r) * (glm::length(o) + r);
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  const double t = -b - s > 0.0 ? -b - s : -b + s;
  if (!(t > 0.0)) return std::nullopt;
  return origin_m + t * d;
}

}  // namespace welkin::editor
