// A panel a module registers as data (model/module_panels.h): its components, each on the first
// entity that has it, drawn by the reflection inspector, with a button to add a missing one.
#include <imgui.h>

#include "ui/field_inspector.h"
#include "ui/panel_registry.h"

namespace welkin::editor {

void draw_component_panel(EditorContext& ctx, const std::vector<std::string>& components) {
  for (const std::string& component : components) {
    ImGui::PushID(component.c_str());
    EntityId id = ctx.doc.entity_with(component);
    if (ImGui::CollapsingHeader(component.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
      if (id == kNoEntity) {
        ImGui::TextDisabled("No entity has %s.", component.c_str());
        if (ImGui::Button("add to a new entity"))
          ctx.attempt([&] { ctx.doc.add_entity(component, nlohmann::json{{component, nlohmann::json::object()}}); });
      } else {
        ImGui::TextDisabled("on '%s'", ctx.doc.display_name(id).c_str());
        draw_component_fields(ctx, id, ctx.doc.require_component(component));
      }
    }
    ImGui::PopID();
  }
}

void register_module_panels(PanelRegistry& registry, const std::vector<ModulePanelSpec>& specs) {
  for (const ModulePanelSpec& spec : specs) {
    std::function<void(EditorContext&)> draw = [components = spec.components](EditorContext& ctx) { draw_component_panel(ctx, components); };
    if (spec.map) draw = [map = *spec.map](EditorContext& ctx) { draw_map_panel(ctx, map); };
    registry.add(EditorPanel{.title = spec.title, .requires_module = spec.module, .draw = std::move(draw)});
  }
}

}  // namespace welkin::editor
