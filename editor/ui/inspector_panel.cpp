// The selected entity: its name, each component (reflection-drawn; the header's close button
// removes it) and a menu of every component the installed modules offer.
#include <imgui.h>
#include <imgui_stdlib.h>

#include "ui/field_inspector.h"
#include "ui/panel_registry.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

void draw_inspector_panel(EditorContext& ctx) {
  EditorDocument& doc = ctx.doc;
  EntityId id = doc.selected();
  if (id == kNoEntity) {
    ImGui::TextDisabled("Select an entity in the outliner.");
    return;
  }
  // The name is edited in a buffer and renamed on release, so typing a name is one undo step; the
  // buffer follows the document whenever it is not being typed in (undo, another selection).
  static std::string name_buffer;
  static bool typing = false;
  static EntityId shown = kNoEntity;
  if (!typing || shown != id) {
    const Name* n = doc.world().registry().get<Name>(doc.entity(id));
    name_buffer = n ? n->value : "";
    shown = id;
  }
  ImGui::InputText("name", &name_buffer);
  typing = ImGui::IsItemActive();
  if (ImGui::IsItemDeactivatedAfterEdit()) ctx.attempt([&] { doc.rename_entity(id, name_buffer); });
  ImGui::Separator();

  std::string remove;
  for (const TypeDesc* type : doc.components_of(id)) {
    if (type->name == Name::kTypeName) continue;
    bool keep = true;
    bool open = ImGui::CollapsingHeader(type->name.c_str(), &keep, ImGuiTreeNodeFlags_DefaultOpen);
    if (ImGui::IsItemHovered() && !type->tooltip.empty()) ImGui::SetTooltip("%s", type->tooltip.c_str());
    if (!keep) remove = type->name;
    if (open) draw_component_fields(ctx, id, *type);
  }
  if (!remove.empty()) ctx.attempt([&] { doc.remove_component(id, remove); });

  ImGui::Separator();
  if (ImGui::BeginCombo("add component", "choose...")) {
    for (const std::string& name : doc.known_components()) {
      if (name == Name::kTypeName || !doc.get_component(id, name).is_null()) continue;
      const ModuleManifest* provider = doc.world().modules().provider_of(name);
      bool loaded = provider && doc.world().modules().is_loaded(provider->name);
      std::string label = loaded ? name : name + "  (loads " + (provider ? provider->name : "?") + ")";
      if (ImGui::Selectable(label.c_str())) ctx.attempt([&] { doc.add_component(id, name); });
    }
    ImGui::EndCombo();
  }
}

}  // namespace welkin::editor
