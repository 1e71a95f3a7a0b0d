// The undo history, newest last; clicking a step undoes or redoes up to it.
#include <imgui.h>

#include "ui/panel_registry.h"

namespace welkin::editor {

void draw_history_panel(EditorContext& ctx) {
  EditorDocument& doc = ctx.doc;
  ImGui::BeginDisabled(!doc.history().can_undo());
  if (ImGui::Button("undo")) ctx.attempt([&] { doc.undo(); });
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!doc.history().can_redo());
  if (ImGui::Button("redo")) ctx.attempt([&] { doc.redo(); });
  ImGui::EndDisabled();
  ImGui::Separator();
  const auto& steps = doc.history().steps();
  size_t cursor = doc.history().cursor();
  if (ImGui::Selectable("(scene as loaded)", cursor == 0))
    while (doc.history().can_undo() && ctx.attempt([&] { doc.undo(); })) {}
  for (size_t i = 0; i < steps.size(); ++i) {
    ImGui::PushID(int(i));
    bool done = i < cursor;
    if (!done) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    if (ImGui::Selectable(steps[i].label.c_str(), i + 1 == cursor)) {
      // Walk the cursor to just after step i.
      while (doc.history().cursor() > i + 1 && ctx.attempt([&] { doc.undo(); })) {}
      while (doc.history().cursor() < i + 1 && ctx.attempt([&] { doc.redo(); })) {}
    }
    if (!done) ImGui::PopStyleColor();
    ImGui::PopID();
  }
}

}  // namespace welkin::editor
