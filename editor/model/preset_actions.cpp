#include "model/preset_actions.h"

#include "model/reflected_object.h"
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

void require_whole(const PresetFile& preset, const std::string& what) {
  if (preset.is_element())
    throw Error(ErrorInfo{.file = preset.file.string(),
                          .path = preset.target(),
                          .message = "cannot " + what + " a preset of one element of an array"});
}

// The entity's array an element preset is of, and the component it is in.
json element_array(EditorDocument& doc, const PresetFile& preset, EntityId entity, json& component) {
  if (!preset.is_element())
    throw Error(ErrorInfo{.file = preset.file.string(),
                          .path = preset.component,
                          .message = "not a preset of an array's element"});
  component = current_value(doc, preset.component, entity);
  return component.value(preset.element_field, json::array());
}

void check_index(const PresetFile& preset, const json& array, size_t index) {
  if (index >= array.size())
    throw Error(ErrorInfo{.path = preset.target() + "/" + std::to_string(index),
                          .expected = "an element index below " + std::to_string(array.size()),
                          .found = std::to_string(index)});
}

}  // namespace

void apply_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  const std::string to = " to '" + doc.display_name(entity) + "'";
  if (!preset.is_element()) {
    doc.set_component(entity, preset.component, presets.complete_value(preset),
                      "Apply preset " + preset.module + "/" + preset.name + to);
    return;
  }
  json element = presets.complete_value(preset);
  json component = doc.get_component(entity, preset.component);
  if (component.is_null()) component = default_component_json(presets.component_type(preset.component));
  component[preset.element_field].push_back(std::move(element));
  doc.set_component(entity, preset.component, component,
                    "Add " + preset.module + "/" + preset.name + " to " + preset.target() + to);
}

void apply_preset_to_element(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                             EntityId entity, size_t index) {
  json element = presets.complete_value(preset);
  json component;
  json array = element_array(doc, preset, entity, component);
  check_index(preset, array, index);
  component[preset.element_field][index] = std::move(element);
  doc.set_component(entity, preset.component, component,
                    "Apply preset " + preset.module + "/" + preset.name + " to " + preset.target() + "/" +
                        std::to_string(index) + " of '" + doc.display_name(entity) + "'");
}

void revert_to_preset_file(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  require_whole(preset, "revert to");
  PresetFile fresh = presets.read(preset.module, preset.file, preset.name);
  if (!fresh.ok()) throw Error(*fresh.error);
  doc.set_component(entity, fresh.component, presets.complete_value(fresh),
                    "Revert '" + doc.display_name(entity) + "' to " + preset.module + "/" + preset.name);
}

void blend_presets(EditorDocument& doc, PresetLibrary& presets, const PresetFile& a, const PresetFile& b, double t,
                   EntityId entity, bool continuous) {
  require_whole(a, "blend");
  require_whole(b, "blend");
  if (a.component != b.component)
    throw Error(ErrorInfo{.expected = "two presets of one component", .found = a.component + " and " + b.component,
                          .message = "cannot blend " + a.name + " and " + b.name});
  if (!(t >= 0.0 && t <= 1.0)) throw Error(ErrorInfo{.path = "blend", .expected = "t in [0, 1]", .found = std::to_string(t)});
  const TypeDesc& type = presets.component_type(a.component);
  json blended = blend_object_json(type, presets.complete_value(a), presets.complete_value(b), t);
  doc.set_component(entity, a.component, blended, "Blend " + a.name + " / " + b.name, continuous);
}

void save_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity) {
  require_whole(preset, "save a whole component over");
  presets.save(preset.component, current_value(doc, preset.component, entity), preset.file);
}

void save_preset_element(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                         EntityId entity, size_t index) {
  json component;
  json array = element_array(doc, preset, entity, component);
  check_index(preset, array, index);
  presets.save_element(preset, array[index]);
}

void save_preset_as(EditorDocument& doc, PresetLibrary& presets, const std::string& component, EntityId entity,
                    const std::filesystem::path& file) {
  presets.save(component, current_value(doc, component, entity), file);
}

std::vector<std::string> preset_differences(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                                            EntityId entity) {
  if (!preset.ok() || preset.is_element()) return {};
  json current = doc.get_component(entity, preset.component);
  if (current.is_null()) return {};
  return differing_fields(presets.component_type(preset.component), current, presets.complete_value(preset));
}

std::vector<std::string> preset_element_differences(EditorDocument& doc, PresetLibrary& presets,
                                                    const PresetFile& preset, EntityId entity, size_t index) {
  if (!preset.ok() || !preset.is_element()) return {};
  json current = doc.get_component(entity, preset.component);
  if (current.is_null()) return {};
  const json array = current.value(preset.element_field, json::array());
  if (index >= array.size()) return {};
  return differing_fields(presets.preset_type(preset), array[index], presets.complete_value(preset));
}

size_t element_count(EditorDocument& doc, const PresetFile& preset, EntityId entity) {
  if (!preset.is_element()) return 0;
  json current = doc.get_component(entity, preset.component);
  return current.is_null() ? 0 : current.value(preset.element_field, json::array()).size();
}

}  // namespace welkin::editor
