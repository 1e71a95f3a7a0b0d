#include "model/editor_document.h"

#include <algorithm>
#include <cmath>

#include "model/reflected_object.h"
#include "welkin/core/error.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

constexpr std::string_view kNameComponent = Name::kTypeName;

std::string step_label(const std::string& verb, const std::string& what) { return verb + " " + what; }

json region_to_json(const MapRegion& r) {
  return {{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}, {"texels", json::binary(r.texels)}};
}

MapRegion region_from_json(const json& j) {
  return MapRegion{j.at("x").get<int>(), j.at("y").get<int>(), j.at("width").get<int>(), j.at("height").get<int>(),
                   j.at("texels").get_binary()};
}

}  // namespace

EditorDocument::EditorDocument(WorldFactory make_world) : make_world_(std::move(make_world)) { new_scene(); }

EditorDocument::~EditorDocument() = default;

// --- Scene -------------------------------------------------------------------------------------

void EditorDocument::new_scene() { replace_world(make_world_(), ""); }

void EditorDocument::replace_world(std::unique_ptr<World> world, const std::string& path) {
  // The history goes with the old world, but the sequence stays open: whether it is saved must
  // survive the clear (a dirty one stays dirty, with no version to undo back to).
  const bool sequence_was_dirty = sequence_dirty();
  world_ = std::move(world);
  ++world_generation_;
  ids_.clear();
  ids_.sync(world_->registry());
  history_.clear();
  preview_originals_.clear();  // they belonged to the old world
  previewing_ = false;
  selected_ = kNoEntity;
  scene_path_ = path;
  mark_saved(DocumentPart::scene);  // a new scene has nothing to lose; a loaded one matches its file
  if (sequence_was_dirty) mark_unsaved(DocumentPart::sequence);
  else mark_saved(DocumentPart::sequence);
}

void EditorDocument::load_scene(const std::string& path) {
  // Load into a fresh world first: a bad file leaves the open scene untouched.
  std::unique_ptr<World> fresh = make_world_();
  load_scene_file(*fresh, path);
  replace_world(std::move(fresh), path);
}

void EditorDocument::save_scene(const std::string& path) {
  end_preview();
  history_.seal();  // a drag still merging would change the scene after it was marked saved
  // The maps first: a scene is never saved naming a painted map that was not written.
  if (PaintedMaps* maps = world_->find_resource<PaintedMaps>()) maps->save_unsaved();
  save_scene_file(*world_, path);
  scene_path_ = path;
  mark_saved(DocumentPart::scene);
}

void EditorDocument::recover_scene(const std::string& file, const std::string& original_path) {
  load_scene(file);
  scene_path_ = original_path;
  mark_unsaved(DocumentPart::scene);
}

void EditorDocument::recover_sequence(const std::string& file, const std::string& original_path) {
  set_sequence(load_sequence_file(file), "Recover sequence");
  sequence_path_ = original_path;
  mark_unsaved(DocumentPart::sequence);
}

// --- Entities ----------------------------------------------------------------------------------

std::vector<EntityRow> EditorDocument::entities() {
  ids_.sync(world_->registry());
  std::vector<EntityRow> rows;
  for (Entity e : world_->registry().entities()) {
    EntityId id = ids_.id_of(e);
    rows.push_back(EntityRow{id, display_name(id)});
  }
  return rows;
}

std::string EditorDocument::display_name(EntityId id) const {
  Entity e = ids_.entity_of(id);
  if (e.is_null()) return "(removed)";
  if (const Name* n = world_->registry().get<Name>(e); n && !n->value.empty()) return n->value;
  return "#" + std::to_string(e.index);
}

EntityId EditorDocument::find_by_name(std::string_view name) {
  ids_.sync(world_->registry());
  for (Entity e : world_->registry().entities())
    if (const Name* n = world_->registry().get<Name>(e); n && n->value == name) return ids_.id_of(e);
  return kNoEntity;
}

EntityId EditorDocument::selected() const {
  return ids_.entity_of(selected_).is_null() ? kNoEntity : selected_;
}

EntityId EditorDocument::entity_with(const std::string& component) {
  TypeId type = type_id_of_name(component);
  Registry& reg = world_->registry();
  if (Entity sel = ids_.entity_of(selected_); !sel.is_null() && reg.has(sel, type)) return selected_;
  if (const ComponentPool* pool = reg.pool(type); pool && !pool->empty()) {
    // The pool is dense, not in creation order: take the earliest entity, as a reader of the file would.
    for (Entity e : reg.entities())
      if (pool->contains(e)) return ids_.id_of(e);
  }
  return kNoEntity;
}

std::vector<const TypeDesc*> EditorDocument::components_of(EntityId id) const {
  Entity e = ids_.entity_of(id);
  if (e.is_null()) return {};
  return world_->registry().components_of(e);
}

const TypeDesc& EditorDocument::require_component(const std::string& component) {
  return *world_->modules().require_component(component).type;
}

std::vector<std::string> EditorDocument::known_components() const {
  std::vector<std::string> names;
  for (const ModuleManifest& m : world_->modules().available())
    names.insert(names.end(), m.components.begin(), m.components.end());
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

Entity EditorDocument::require_entity(EntityId id) const {
  Entity e = ids_.entity_of(id);
  if (e.is_null() || !world_->registry().valid(e))
    throw Error(ErrorInfo{.expected = "an existing entity", .found = "entity id " + std::to_string(id), .message = "no such entity"});
  return e;
}

// --- Reading -----------------------------------------------------------------------------------

json EditorDocument::get_component(EntityId id, const std::string& component) const {
  Entity e = ids_.entity_of(id);
  const ComponentInfo* info = world_->modules().component(component);
  if (e.is_null() || !info) return nullptr;
  const void* data = world_->registry().get(e, info->type->id);
  return data ? object_to_json(*info->type, data) : json(nullptr);
}

json EditorDocument::get_field(EntityId id, const std::string& component, const std::string& path) const {
  Entity e = require_entity(id);
  const ComponentInfo* info = world_->modules().component(component);
  const void* data = info ? world_->registry().get(e, info->type->id) : nullptr;
  if (!data)
    throw Error(ErrorInfo{.path = component, .message = "entity '" + display_name(id) + "' has no " + component + " component"});
  // resolve_field needs a mutable object; it only reads here.
  try {
    return resolve_field(*info->type, const_cast<void*>(data), path).get_json();
  } catch (const Error& err) {
    throw err.with_path_prefix(component);
  }
}

const void* EditorDocument::component_data(EntityId id, const TypeDesc& type) const {
  Entity e = ids_.entity_of(id);
  return e.is_null() ? nullptr : world_->registry().get(e, type.id);
}

json EditorDocument::entity_snapshot(EntityId id) const {
  Entity e = require_entity(id);
  const Registry& reg = world_->registry();
  json snapshot = json::object();
  if (const Name* n = reg.get<Name>(e)) snapshot["name"] = n->value;
  json components = json::object();
  for (const TypeDesc* t : reg.components_of(e))
    if (t->name != kNameComponent) components[t->name] = object_to_json(*t, reg.get(e, t->id));
  snapshot["components"] = std::move(components);
  return snapshot;
}

// --- Edits -------------------------------------------------------------------------------------

EntityId EditorDocument::add_entity(const std::string& name, const json& components) {
  end_preview();
  // The id is fixed now, so redo re-creates the entity under the id later edits refer to.
  EntityId id = ids_.reserve();
  Edit edit{.target = EditTarget::entity, .entity = id, .before = nullptr,
            .after = json{{"name", name}, {"components", components}}};
  execute(std::move(edit), step_label("Add entity", "'" + name + "'"), false);
  selected_ = id;
  return id;
}

void EditorDocument::remove_entity(EntityId id) {
  end_preview();
  Edit edit{.target = EditTarget::entity, .entity = id, .before = entity_snapshot(id), .after = nullptr};
  execute(std::move(edit), step_label("Remove entity", "'" + display_name(id) + "'"), false);
}

void EditorDocument::rename_entity(EntityId id, const std::string& name) {
  require_entity(id);
  if (get_component(id, std::string(kNameComponent)).is_null())
    set_component(id, std::string(kNameComponent), json{{"value", name}}, "Rename '" + display_name(id) + "'");
  else
    set_field(id, std::string(kNameComponent), "value", name);
}

void EditorDocument::add_component(EntityId id, const std::string& component) {
  end_preview();
  const TypeDesc& type = require_component(component);
  if (!get_component(id, component).is_null())
    throw Error(ErrorInfo{.path = component, .message = "entity '" + display_name(id) + "' already has " + component});
  Edit edit{.target = EditTarget::component, .entity = id, .component = component, .before = nullptr,
            .after = default_component_json(type)};
  execute(std::move(edit), step_label("Add", component + " to '" + display_name(id) + "'"), false);
}

void EditorDocument::remove_component(EntityId id, const std::string& component) {
  end_preview();
  json before = get_component(id, component);
  if (before.is_null())
    throw Error(ErrorInfo{.path = component, .message = "entity '" + display_name(id) + "' has no " + component + " component"});
  Edit edit{.target = EditTarget::component, .entity = id, .component = component, .before = std::move(before), .after = nullptr};
  execute(std::move(edit), step_label("Remove", component + " from '" + display_name(id) + "'"), false);
}

void EditorDocument::set_field(EntityId id, const std::string& component, const std::string& path, const json& value,
                               bool continuous) {
  end_preview();
  Edit edit{.target = EditTarget::field, .entity = id, .component = component, .path = path,
            .before = get_field(id, component, path), .after = value};
  execute(std::move(edit), step_label("Set", component + "/" + path + " on '" + display_name(id) + "'"), continuous);
}

void EditorDocument::set_component(EntityId id, const std::string& component, const json& value, const std::string& label,
                                   bool continuous) {
  end_preview();
  require_entity(id);
  const TypeDesc& type = require_component(component);
  Edit edit{.target = EditTarget::component, .entity = id, .component = component,
            .before = get_component(id, component), .after = complete_component_json(type, value)};
  execute(std::move(edit), label, continuous);
}

void EditorDocument::set_sequence(Sequence sequence, const std::string& label, bool continuous) {
  end_preview();
  Edit edit{.target = EditTarget::sequence, .before = sequence_to_json(sequence_), .after = sequence_to_json(sequence)};
  execute(std::move(edit), label, continuous);
}

void EditorDocument::execute(Edit edit, const std::string& label, bool continuous) {
  if (!continuous && edit.before == edit.after) {
    history_.seal();
    return;  // nothing changes: no empty undo steps
  }
  apply(edit, edit.after);
  // What was stored may differ from what was asked (a float rounds): record the stored value, so
  // undo/redo reproduce exactly what the user saw.
  if (edit.target == EditTarget::field) edit.after = get_field(edit.entity, edit.component, edit.path);
  history_.record(std::move(edit), label, continuous);
}

bool EditorDocument::undo() {
  end_preview();
  history_.seal();
  const HistoryStep* step = history_.next_undo();
  if (!step) return false;
  for (auto it = step->edits.rbegin(); it != step->edits.rend(); ++it) apply(*it, it->before);
  history_.moved_back();
  return true;
}

bool EditorDocument::redo() {
  end_preview();
  history_.seal();
  const HistoryStep* step = history_.next_redo();
  if (!step) return false;
  for (const Edit& e : step->edits) apply(e, e.after);
  history_.moved_forward();
  return true;
}

void EditorDocument::apply(const Edit& edit, const json& value) {
  Registry& reg = world_->registry();
  switch (edit.target) {
    case EditTarget::field: {
      Entity e = require_entity(edit.entity);
      const TypeDesc& type = require_component(edit.component);
      void* data = reg.get(e, type.id);
      if (!data)
        throw Error(ErrorInfo{.path = edit.component, .message = "entity '" + display_name(edit.entity) + "' has no " +
                                                                 edit.component + " component"});
      ReflectedObject copy(type, data);
      try {
        resolve_field(type, copy.get(), edit.path).set_json(value);
      } catch (const Error& err) {
        throw err.with_path_prefix(edit.component);
      }
      copy.copy_to(data);
      return;
    }
    case EditTarget::component: {
      Entity e = require_entity(edit.entity);
      const TypeDesc& type = require_component(edit.component);
      if (value.is_null()) {
        reg.remove(e, type.id);
        return;
      }
      ReflectedObject object(type);
      try {
        object.read(value);
      } catch (const Error& err) {
        throw err.with_path_prefix(edit.component);
      }
      void* data = reg.has(e, type.id) ? reg.get(e, type.id) : reg.emplace(e, type);
      object.copy_to(data);
      return;
    }
    case EditTarget::entity: {
      if (value.is_null()) {
        Entity e = require_entity(edit.entity);
        reg.destroy(e);
        ids_.unbind(edit.entity);
        return;
      }
      // Validate every component before creating anything.
      std::vector<std::pair<const TypeDesc*, std::unique_ptr<ReflectedObject>>> parts;
      if (auto comps = value.find("components"); comps != value.end()) {
        for (auto it = comps->begin(); it != comps->end(); ++it) {
          const TypeDesc& type = require_component(it.key());
          auto object = std::make_unique<ReflectedObject>(type);
          try {
            object->read(it.value());
          } catch (const Error& err) {
            throw err.with_path_prefix(it.key());
          }
          parts.emplace_back(&type, std::move(object));
        }
      }
      Entity e = reg.create();
      ids_.bind(edit.entity, e);
      if (auto n = value.find("name"); n != value.end() && n->is_string()) reg.emplace<Name>(e).value = n->get<std::string>();
      for (auto& [type, object] : parts) object->copy_to(reg.emplace(e, *type));
      return;
    }
    case EditTarget::sequence: sequence_ = sequence_from_json(value, "sequence"); return;
    case EditTarget::map: {
      PaintedMap& map = world_->resource<PaintedMaps>().edit(edit.path);
      paste_region(map, region_from_json(value));
      PaintedMaps::touched(map);
      return;
    }
  }
}

// --- Painted maps ------------------------------------------------------------------------------

bool EditorDocument::paint_map(const std::string& file, const BrushStamp& stamp, bool continuous) {
  PaintedMap& map = world_->resource<PaintedMaps>().edit(file);
  const MapRegion touched = brush_bounds(map, stamp);
  if (touched.width == 0) return false;
  Edit edit{.target = EditTarget::map, .path = file};
  // A stroke is one edit over the rectangle of all its stamps: what that rectangle held before the
  // stroke (the texels it had changed come from the stroke's own record) and holds after it.
  Edit* stroke = continuous ? history_.open_edit(edit) : nullptr;
  MapRegion bounds = touched;
  const MapRegion earlier = stroke ? region_from_json(stroke->before) : MapRegion{};
  if (stroke) {
    const int x0 = std::min(bounds.x, earlier.x), y0 = std::min(bounds.y, earlier.y);
    const int x1 = std::max(bounds.x + bounds.width, earlier.x + earlier.width);
    const int y1 = std::max(bounds.y + bounds.height, earlier.y + earlier.height);
    bounds = {x0, y0, x1 - x0, y1 - y0, {}};
  }
  MapRegion before = copy_region(map, bounds.x, bounds.y, bounds.width, bounds.height);
  if (stroke) paste_region(before, earlier);
  apply_brush(map, stamp);
  PaintedMaps::touched(map);
  edit.before = region_to_json(before);
  edit.after = region_to_json(copy_region(map, bounds.x, bounds.y, bounds.width, bounds.height));
  if (stroke) {
    stroke->before = std::move(edit.before);
    stroke->after = std::move(edit.after);
    history_.trim();
  } else {
    history_.record(std::move(edit), "Paint " + file, continuous);
  }
  return true;
}

// --- Timeline ----------------------------------------------------------------------------------

void EditorDocument::load_sequence(const std::string& path) {
  Sequence loaded = load_sequence_file(path);
  set_sequence(std::move(loaded), "Load sequence " + path);
  history_.seal();
  sequence_path_ = path;
  mark_saved(DocumentPart::sequence);  // it matches its file; undoing the load makes it dirty
}

void EditorDocument::save_sequence(const std::string& path) {
  history_.seal();
  save_sequence_file(path, sequence_);
  sequence_path_ = path;
  mark_saved(DocumentPart::sequence);
}

// Each track goes through welkin::apply_sequence on its own (as the engine plays it), so one
// that cannot be applied is reported and the others still are.
std::vector<std::string> EditorDocument::preview_sequence(double time_s) {
  std::vector<std::string> problems;
  previewing_ = true;
  for (const SequenceTrack& track : sequence_.tracks) {
    keep_preview_originals(split_track_target(track.target).component);
    try {
      apply_sequence(welkin::Sequence{.tracks = {to_runtime_track(track)}}, *world_, time_s);
    } catch (const Error& err) {
      // apply_sequence locates its errors in the file; the message says what went wrong.
      problems.push_back(track.target + ": " + (err.info().message.empty() ? format_error(err.info()) : err.info().message));
    }
  }
  return problems;
}

// Every entity's copy of a tracked component is kept (the track's own entity rule stays in
// apply_sequence alone): components are small, and the first preview of each is all that is kept.
void EditorDocument::keep_preview_originals(const std::string& component) {
  const ComponentInfo* info = world_->modules().component(component);
  if (!info) return;  // apply_sequence reports it
  const ComponentPool* pool = world_->registry().pool(info->type->id);
  if (!pool) return;
  for (Entity e : pool->entities()) {
    const EntityId id = ids_.id_of(e);
    const bool kept = std::any_of(preview_originals_.begin(), preview_originals_.end(),
                                  [&](const PreviewOriginal& o) { return o.entity == id && o.component == component; });
    if (!kept) preview_originals_.push_back({id, component, get_component(id, component)});
  }
}

void EditorDocument::end_preview() {
  for (const PreviewOriginal& o : preview_originals_) {
    const Entity e = ids_.entity_of(o.entity);
    if (e.is_null() || !world_->registry().valid(e)) continue;  // a system removed it: nothing to put back
    apply(Edit{.target = EditTarget::component, .entity = o.entity, .component = o.component}, o.value);
  }
  preview_originals_.clear();
  previewing_ = false;
}

}  // namespace welkin::editor
