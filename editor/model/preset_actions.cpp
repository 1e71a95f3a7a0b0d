#include "model/preset_actions.h"

#include "model/value_blend.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

json current_value(EditorDocument& doc, const std::string& component, EntityId entity) {
  json value = doc.get_component(entity, component);
  if (value.is_null())
    throw Error(ErrorInfo{.path = component, .message = "entity '" + doc.display_name(entity) + "' has no " + component + " component"});
  return value;
}

}  // namespace

void apply_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  doc.set_component(entity, preset.component, presets.complete_value(preset),
                    "Apply preset " + preset.module + "/" + preset.name + " to '" + doc.display_name(entity) + "'");
}

void revert_to_preset_file(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  PresetFile fresh = presets.read(preset.module, preset.file);
  if (!fresh.ok()) throw Error(*fresh.error);
  doc.set_component(entity, fresh.component, presets.complete_value(fresh),
                    "Revert '" + doc.display_name(entity) + "' to " + preset.module + "/" + preset.name);
}

void blend_presets(EditorDocument& doc, PresetLibrary& presets, const PresetFile& a, const PresetFile& b, double t,
                   EntityId entity, bool continuous) {
  if (a.component != b.component)
    throw Error(ErrorInfo{.expected = "two presets of one component", .found = a.component + " and " + b.component,
                          .message = "cannot blend " + a.name + " and " + b.name});
  if (!(t >= 0.0 && t <= 1.0)) throw Error(ErrorInfo{.path = "blend", .expected = "t in [0, 1]", .found = std::to_string(t)});
  const TypeDesc& type = presets.component_type(a.component);
  json blended = blend_object_json(type, presets.complete_value(a), presets.complete_value(b), t);
  doc.set_component(entity, a.component, blended, "Blend " + a.name + " / " + b.name, continuous);
}

void save_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  presets.save(preset.component, current_value(doc, preset.component, entity), preset.file);
}

void save_preset_as(EditorDocument& doc, PresetLibrary& presets, const std::string& component, EntityId entity,
                    const std::filesystem::path& file) {
  presets.save(component, current_value(doc, component, entity), file);
}

std::vector<std::string> preset_differences(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                                            EntityId entity) {
  if (!preset.ok()) return {};
  json current = doc.get_component(entity, preset.component);
  if (current.is_null()) return {};
  return differing_fields(presets.component_type(preset.component), current, presets.complete_value(preset));
}

}  // namespace welkin::editor
