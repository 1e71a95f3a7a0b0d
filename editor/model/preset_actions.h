#pragma once
// What the preset browser and the script do with presets, as undoable document edits.
#include <filesystem>
#include <string>
#include <vector>

#include "model/editor_document.h"
#include "model/preset_library.h"

namespace welkin::editor {

// Sets the entity's component to the preset (declared defaults where the file is silent); adds the
// component when the entity lacks it. An element preset (a cloud layer of a genus) is added at the end
// of its array instead, the array's bound checked. One undo step.
void apply_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Sets element `index` of the array an element preset is of to the preset; throws Error naming the
// array when there is no such element or the preset is of a whole component. One undo step.
void apply_preset_to_element(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                             EntityId entity, size_t index);
// Re-reads the preset's file from disk (it may have changed) and applies it (whole components only).
void revert_to_preset_file(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Sets the entity's component to the blend of two presets of one component at t in [0, 1] (numeric
// fields lerp, see value_blend.h). `continuous` merges a slider drag into one undo step.
void blend_presets(EditorDocument& doc, PresetLibrary& presets, const PresetFile& a, const PresetFile& b, double t,
                   EntityId entity, bool continuous = false);
// Writes the entity's current component over the preset's own file.
void save_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Writes element `index` of the entity's array over an element preset's own file.
void save_preset_element(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                         EntityId entity, size_t index);
// Writes the entity's current `component` to a new preset file.
void save_preset_as(EditorDocument& doc, PresetLibrary& presets, const std::string& component, EntityId entity,
                    const std::filesystem::path& file);
// Field paths where the entity's component differs from the preset file.
std::vector<std::string> preset_differences(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                                            EntityId entity);
// Field paths where element `index` of the entity's array differs from an element preset's file.
std::vector<std::string> preset_element_differences(EditorDocument& doc, PresetLibrary& presets,
                                                    const PresetFile& preset, EntityId entity, size_t index);
// How many elements the entity's array has that an element preset is of (0 without the component).
size_t element_count(EditorDocument& doc, const PresetFile& preset, EntityId entity);

}  // namespace welkin::editor
