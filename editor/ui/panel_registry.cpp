#include "ui/panel_registry.h"

namespace welkin::editor {

void PanelRegistry::add(EditorPanel panel) {
  if (EditorPanel* existing = find(panel.title)) *existing = std::move(panel);
  else panels_.push_back(std::move(panel));
}

EditorPanel* PanelRegistry::find(std::string_view title) {
  for (auto& p : panels_)
    if (p.title == title) return &p;
  return nullptr;
}

bool PanelRegistry::available(const EditorPanel& panel, const EditorContext& ctx) const {
  return panel.requires_module.empty() || ctx.doc.world().modules().is_loaded(panel.requires_module);
}

void register_builtin_panels(PanelRegistry& r) {
  r.add({"Viewport", "", draw_viewport_panel});
  r.add({"Outliner", "", draw_outliner_panel});
  r.add({"Inspector", "", draw_inspector_panel});
  r.add({"Presets", "", draw_preset_panel});
  r.add({"Timeline", "", draw_timeline_panel});
  // The timeofday module's panel (sun time, date, location are its fields), shown once a scene loads
  // the module; the module can take it over by declaring "Time of day" in editor/panels.json.
  r.add({"Time of day", "timeofday", [](EditorContext& ctx) {
           if (const ModuleManifest* m = ctx.doc.world().modules().manifest("timeofday")) draw_component_panel(ctx, m->components);
         }});
  r.add({"Profiler", "", draw_profiler_panel});
  r.add({"History", "", draw_history_panel});
}

}  // namespace welkin::editor
