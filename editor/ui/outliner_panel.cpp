// The scene's entities: select, add, duplicate, remove (all undoable).
#include <imgui.h>

#include "ui/panel_registry.h"

namespace welkin::editor {

void draw_outliner_panel(EditorContext& ctx) {
  EditorDocument& doc = ctx.doc;
  if (ImGui::Button("add entity")) ctx.attempt([&] { doc.add_entity("entity " + std::to_string(doc.entities().size() + 1)); });
  ImGui::SameLine();
  EntityId selected = doc.selected();
  ImGui::BeginDisabled(selected == kNoEntity);
  if (ImGui::Button("duplicate")) {
    ctx.attempt([&] {
      nlohmann::json components = nlohmann::json::object();
      for (const TypeDesc* t : doc.components_of(selected))
        if (t->name != "core.Name") components[t->name] = doc.get_component(selected, t->name);
      doc.add_entity(doc.display_name(selected) + " copy", components);
    });
  }
  ImGui::SameLine();
  if (ImGui::Button("remove")) ctx.attempt([&] { doc.remove_entity(selected); });
  ImGui::EndDisabled();
  ImGui::Separator();

  ImGui::BeginChild("entities");
  for (const EntityRow& row : doc.entities()) {
    ImGui::PushID(int(row.id));
    std::string kinds;
    for (const TypeDesc* t : doc.components_of(row.id))
      if (t->name != "core.Name") kinds += (kinds.empty() ? "" : ", ") + t->name;
    if (ImGui::Selectable(row.name.c_str(), row.id == selected)) doc.select(row.id);
    if (ImGui::IsItemHovered() && !kinds.empty()) ImGui::SetTooltip("%s", kinds.c_str());
    ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
    ImGui::TextDisabled("%s", kinds.c_str());
    ImGui::PopID();
  }
  ImGui::EndChild();
}

}  // namespace welkin::editor
