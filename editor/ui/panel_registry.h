#pragma once
// Panels are registered, not hard-wired: the built-in ones and those a module contributes (its
// editor part registers them, as flecs/Lumix modules do) go through the same list. A panel that
// names a module is shown only while the scene's world has that module loaded.
#include <functional>
#include <string>
#include <vector>

#include "model/module_panels.h"
#include "ui/editor_context.h"

namespace welkin::editor {

struct EditorPanel {
  std::string title;            // window title and the Panels menu entry
  std::string requires_module;  // empty: always available
  std::function<void(EditorContext&)> draw;  // between ImGui::Begin and End
  bool open = true;
};

class PanelRegistry {
 public:
  void add(EditorPanel panel);
  std::vector<EditorPanel>& panels() { return panels_; }
  EditorPanel* find(std::string_view title);
  bool available(const EditorPanel& panel, const EditorContext& ctx) const;

 private:
  std::vector<EditorPanel> panels_;
};

// The editor's own panels (viewport, outliner, inspector, presets, timeline, profiler, history)
// and, until the timeofday module declares its own in editor/panels.json, a "Time of day" panel of
// its components.
void register_builtin_panels(PanelRegistry& registry);
// Panels modules declare as data; a module's panel replaces a built-in one of the same title.
void register_module_panels(PanelRegistry& registry, const std::vector<ModulePanelSpec>& specs);

// Each built-in panel's body.
void draw_viewport_panel(EditorContext& ctx);
void draw_outliner_panel(EditorContext& ctx);
void draw_inspector_panel(EditorContext& ctx);
void draw_preset_panel(EditorContext& ctx);
void draw_timeline_panel(EditorContext& ctx);
// The listed components, each on the first entity that has it (module panels are this).
void draw_component_panel(EditorContext& ctx, const std::vector<std::string>& components);
void draw_profiler_panel(EditorContext& ctx);
// A module's painted map (model/map_painting.h) and its brush.
void draw_map_panel(EditorContext& ctx, const MapFieldSpec& spec);
// A stamp of the map brush where the viewport's pixel looks (when a map panel turned it on).
void paint_in_viewport(EditorContext& ctx, glm::dvec2 pixel);
// Closes the brush stroke once the mouse button is up (one undo step per stroke).
void end_map_stroke(EditorContext& ctx);
void draw_history_panel(EditorContext& ctx);

}  // namespace welkin::editor
