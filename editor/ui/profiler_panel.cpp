// What a frame costs and what ran: per-pass GPU and CPU times from the render graph, the passes it
// culled, the systems that ran, and which modules are installed and loaded.
#include <imgui.h>

#include <algorithm>

#include "ui/panel_registry.h"

namespace welkin::editor {

void draw_profiler_panel(EditorContext& ctx) {
  const FrameStats& st = ctx.stats;
  ImGui::Text("frame %.2f ms (%.0f fps)   GPU %.3f ms", st.cpu_frame_ms, st.cpu_frame_ms > 0 ? 1000.0 / st.cpu_frame_ms : 0.0,
              st.gpu_total_ms);
  float peak = *std::max_element(st.frame_ms_history.begin(), st.frame_ms_history.end());
  ImGui::PlotLines("##frame ms", st.frame_ms_history.data(), int(st.frame_ms_history.size()), int(st.history_cursor), "frame ms",
                   0.0f, std::max(peak, 1.0f) * 1.1f, ImVec2(ImGui::GetContentRegionAvail().x, 50));  // 1.86 takes no negative widths here

  if (ImGui::CollapsingHeader("Render passes", ImGuiTreeNodeFlags_DefaultOpen)) {
    double gpu_max = 0;
    for (const auto& t : st.last.timings) gpu_max = std::max(gpu_max, t.gpu_ms);
    if (ImGui::BeginTable("passes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingStretchProp)) {
      ImGui::TableSetupColumn("pass");
      ImGui::TableSetupColumn("GPU ms");
      ImGui::TableSetupColumn("CPU ms");
      ImGui::TableSetupColumn("share");
      ImGui::TableHeadersRow();
      for (const auto& t : st.last.timings) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(t.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", t.gpu_ms);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", t.cpu_ms);
        ImGui::TableNextColumn();
        ImGui::ProgressBar(gpu_max > 0 ? float(t.gpu_ms / gpu_max) : 0.0f, ImVec2(-1, 0), "");
      }
      ImGui::EndTable();
    }
    if (st.kept) ImGui::TextDisabled("settled: nothing changed for %d frames, the last frame is shown", ctx.viewport.settled.frames);
    else if (st.last.timings.empty()) ImGui::TextDisabled("no frame rendered yet");
  }
  if (ImGui::CollapsingHeader("Culled passes", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (st.last.culled_passes.empty()) ImGui::TextDisabled("none: every pass reaches the output");
    for (const auto& name : st.last.culled_passes) ImGui::BulletText("%s", name.c_str());
  }
  if (ImGui::CollapsingHeader("Systems run")) {
    for (const auto& name : st.last.systems_run) ImGui::BulletText("%s", name.c_str());
  }
  if (ImGui::CollapsingHeader("Modules", ImGuiTreeNodeFlags_DefaultOpen)) {
    const ModuleHost& host = ctx.doc.world().modules();
    for (const ModuleManifest& m : host.available()) {
      bool loaded = host.is_loaded(m.name);
      ImGui::PushStyleColor(ImGuiCol_Text, loaded ? ImGui::GetStyleColorVec4(ImGuiCol_Text) : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      bool open = ImGui::TreeNode(m.name.c_str(), "%s %s  %s", m.name.c_str(), m.version.c_str(), loaded ? "(loaded)" : "(not loaded: no component in use)");
      ImGui::PopStyleColor();
      if (open) {
        if (!m.description.empty()) ImGui::TextWrapped("%s", m.description.c_str());
        ImGui::TextDisabled("from %s", m.origin.c_str());
        for (const auto& c : m.components) ImGui::BulletText("%s", c.c_str());
        ImGui::TreePop();
      }
    }
  }
}

}  // namespace welkin::editor
