#pragma once
// What the preset browser and the script do with presets, as undoable document edits.
#include <filesystem>
#include <string>
#include <vector>

#include "model/editor_document.h"
#include "model/preset_library.h"

namespace welkin::editor {

// Sets the entity's component to the preset (declared defaults where the file is silent); adds the
// component when the entity lacks it. One undo step.
void apply_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Re-reads the preset's file from disk (it may have changed) and applies it.
void revert_to_preset_file(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Sets the entity's component to the blend of two presets of one component at t in [0, 1] (numeric
// fields lerp, see value_blend.h). `continuous` merges a slider drag into one undo step.
void blend_presets(EditorDocument& doc, PresetLibrary& presets, const PresetFile& a, const PresetFile& b, double t,
                   EntityId entity, bool continuous = false);
// Writes the entity's current component over the preset's own file.
void save_preset(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset, EntityId entity);
// Writes the entity's current `component` to a new preset file.
void save_preset_as(EditorDocument& doc, PresetLibrary& presets, const std::string& component, EntityId entity,
                    const std::filesystem::path& file);
// Field paths where the entity's component differs from the preset file.
std::vector<std::string> preset_differences(EditorDocument& doc, PresetLibrary& presets, const PresetFile& preset,
                                            EntityId entity);

}  // namespace welkin::editor
