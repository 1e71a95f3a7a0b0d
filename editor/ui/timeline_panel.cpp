// The timeline of a sequence file: a playhead that previews the sequence in the scene, one row
// per track with its keys (drag to move, right-click to delete), and file load/save. Keys are
// added from the inspector (a field's context menu: "Key at playhead") or here from the current
// value of a target. Every change of the sequence is an undoable edit.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "ui/panel_registry.h"
#include "welkin/core/error.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

namespace {

struct TimelinePanelState {
  std::string file = "assets/sequences/untitled.json";
  std::string new_target = "core.DirectionalLight/elevation_deg";
  int dragged_track = -1;
  double dragged_from_s = 0;
  double dragged_to_s = 0;
};

void key_current_value(EditorContext& ctx, const std::string& entity_name, const std::string& target) {
  TrackTarget t = split_track_target(target);
  EntityId id = entity_name.empty() ? ctx.doc.entity_with(t.component) : ctx.doc.find_by_name(entity_name);
  if (id == kNoEntity) throw Error("no entity for track " + target);
  nlohmann::json value = ctx.doc.get_field(id, t.component, t.path);
  ctx.doc.set_sequence(with_key(ctx.doc.sequence(), entity_name, target, ctx.timeline.playhead_s, value), "Key " + target);
}

}  // namespace

void draw_timeline_panel(EditorContext& ctx) {
  static TimelinePanelState s;
  static std::string followed_path;  // the file field follows the document's sequence file when it changes
  EditorDocument& doc = ctx.doc;
  if (!doc.sequence_path().empty() && doc.sequence_path() != followed_path) s.file = followed_path = doc.sequence_path();
  TimelineState& tl = ctx.timeline;
  const Sequence& seq = doc.sequence();

  // Transport.
  if (ImGui::Button(tl.playing ? "pause" : "play")) tl.playing = !tl.playing;
  ImGui::SameLine();
  ImGui::Checkbox("loop", &tl.loop);
  ImGui::SameLine();
  ImGui::Checkbox("preview in scene", &tl.preview);
  ImGui::SameLine();
  float duration = float(seq.duration_s);
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
  if (ImGui::DragFloat("duration [s]", &duration, 0.5f, 0.1f, 1e6f, "%.1f", ImGuiSliderFlags_AlwaysClamp)) {
    Sequence changed = seq;
    changed.duration_s = duration;
    ctx.attempt([&] { doc.set_sequence(changed, "Set sequence duration", true); });
  }
  if (ImGui::IsItemDeactivatedAfterEdit()) doc.end_continuous_edit();
  float playhead = float(tl.playhead_s);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##playhead", &playhead, 0.0f, float(doc.sequence().duration_s), "t = %.2f s")) tl.playhead_s = playhead;

  // Tracks: label column, then a strip where x is time.
  // The label column fits the longest track name, up to half the panel.
  auto track_label = [](const SequenceTrack& t) { return (t.entity.empty() ? std::string("*") : t.entity) + ": " + t.target; };
  float label_width = ImGui::GetFontSize() * 12;
  for (const SequenceTrack& t : doc.sequence().tracks) label_width = std::max(label_width, ImGui::CalcTextSize(track_label(t).c_str()).x);
  label_width = std::min(label_width + ImGui::GetStyle().ItemSpacing.x * 2, ImGui::GetContentRegionAvail().x * 0.5f);
  const float row_height = ImGui::GetFrameHeight();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  double span = std::max(doc.sequence().duration_s, 1e-3);
  int remove_track = -1;
  double remove_time = 0;
  for (int ti = 0; ti < int(doc.sequence().tracks.size()); ++ti) {
    const SequenceTrack track = doc.sequence().tracks[size_t(ti)];  // a copy: edits below replace the sequence
    ImGui::PushID(ti);
    std::string label = track_label(track);
    ImGui::TextUnformatted(label.c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s\n%zu keys, %s%s\nright-click: track settings", track.target.c_str(), track.keys.size(),
                        interpolation_name(track.interpolation), track.optional ? ", optional" : "");
    if (ImGui::BeginPopupContextItem("track settings")) {
      // Each setting is an undoable change of the sequence, like key edits.
      SequenceTrack edited = track;
      bool changed = false;
      int interpolation = int(edited.interpolation);
      if (ImGui::Combo("interpolation", &interpolation, "step\0linear\0smooth\0cubic\0")) {
        edited.interpolation = Interpolation(interpolation);
        changed = true;
      }
      float wrap = float(edited.wrap);
      if (ImGui::InputFloat("wrap (0: none, 360: degrees, 24: hours)", &wrap, 0, 0, "%g", ImGuiInputTextFlags_EnterReturnsTrue)) {
        edited.wrap = std::max(0.0, double(wrap));
        changed = true;
      }
      if (ImGui::Checkbox("optional (skip when the component is missing)", &edited.optional)) changed = true;
      if (changed) {
        Sequence next = doc.sequence();
        next.tracks[size_t(ti)] = edited;
        ctx.attempt([&] { doc.set_sequence(next, "Track settings " + track.target); });
      }
      if (ImGui::MenuItem("delete track")) {
        Sequence next = doc.sequence();
        next.tracks.erase(next.tracks.begin() + ti);
        ctx.attempt([&] { doc.set_sequence(next, "Delete track " + track.target); });
        ImGui::EndPopup();
        ImGui::PopID();
        break;
      }
      ImGui::EndPopup();
    }
    ImGui::SameLine(label_width);
    if (ImGui::SmallButton("key")) ctx.attempt([&] { key_current_value(ctx, track.entity, track.target); });
    ImGui::SameLine();
    ImVec2 origin = ImGui::GetCursorScreenPos();
    float width = std::max(ImGui::GetContentRegionAvail().x, 50.0f);
    ImGui::InvisibleButton("strip", ImVec2(width, row_height));
    draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + row_height), ImGui::GetColorU32(ImGuiCol_FrameBg));
    auto x_of = [&](double t) { return origin.x + float(t / span) * width; };
    auto t_of = [&](float x) { return std::clamp(double(x - origin.x) / width * span, 0.0, span); };
    // Keys: drag moves (one undo step per drag), right click deletes.
    for (size_t k = 0; k < track.keys.size(); ++k) {
      double t = track.keys[k].t;
      if (s.dragged_track == ti && std::abs(t - s.dragged_from_s) < kKeyTimeEpsilon) t = s.dragged_to_s;
      ImVec2 c(x_of(t), origin.y + row_height * 0.5f);
      float r = row_height * 0.3f;
      bool hot = std::abs(ImGui::GetIO().MousePos.x - c.x) < r + 2 && std::abs(ImGui::GetIO().MousePos.y - c.y) < r + 2;
      draw->AddQuadFilled(ImVec2(c.x, c.y - r), ImVec2(c.x + r, c.y), ImVec2(c.x, c.y + r), ImVec2(c.x - r, c.y),
                          ImGui::GetColorU32(hot ? ImGuiCol_PlotHistogramHovered : ImGuiCol_PlotHistogram));
      if (hot && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("t = %.3f s\n%s\nright-click: delete", track.keys[k].t, track.keys[k].value.dump().c_str());
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
          s.dragged_track = ti;
          s.dragged_from_s = s.dragged_to_s = track.keys[k].t;
        }
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) remove_track = ti, remove_time = track.keys[k].t;
      }
    }
    if (s.dragged_track == ti) {
      if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        s.dragged_to_s = t_of(ImGui::GetIO().MousePos.x);
      } else {
        if (std::abs(s.dragged_to_s - s.dragged_from_s) > kKeyTimeEpsilon) {
          Sequence moved = with_key_moved(doc.sequence(), track.entity, track.target, s.dragged_from_s, s.dragged_to_s);
          ctx.attempt([&] { doc.set_sequence(moved, "Move key " + track.target); });
        }
        s.dragged_track = -1;
      }
    } else if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
      tl.playhead_s = t_of(ImGui::GetIO().MousePos.x);  // click on the strip scrubs
    }
    float px = x_of(tl.playhead_s);
    draw->AddLine(ImVec2(px, origin.y), ImVec2(px, origin.y + row_height), ImGui::GetColorU32(ImGuiCol_PlotLinesHovered), 2.0f);
    ImGui::PopID();
  }
  if (remove_track >= 0) {
    const SequenceTrack& t = doc.sequence().tracks[size_t(remove_track)];
    Sequence changed = without_key(doc.sequence(), t.entity, t.target, remove_time);
    ctx.attempt([&] { doc.set_sequence(changed, "Delete key " + t.target); });
  }
  for (const auto& problem : tl.problems) ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "%s", problem.c_str());
  if (doc.sequence().tracks.empty()) ImGui::TextDisabled("No tracks. Key a field from its context menu in the inspector, or add one below.");

  ImGui::Separator();
  ImGui::SetNextItemWidth(label_width);
  ImGui::InputText("##target", &s.new_target);
  ImGui::SameLine();
  if (ImGui::Button("key target at playhead")) {
    ctx.attempt([&] {
      TrackTarget t = split_track_target(s.new_target);
      EntityId id = doc.entity_with(t.component);
      std::string name;
      if (id != kNoEntity)
        if (const Name* n = doc.world().registry().get<Name>(doc.entity(id))) name = n->value;
      key_current_value(ctx, name, s.new_target);
    });
  }
  ImGui::SetNextItemWidth(label_width);
  ImGui::InputText("##file", &s.file);
  ImGui::SameLine();
  if (ImGui::Button("load")) ctx.attempt([&] { ctx.session.request(GuardedAction::open_sequence, s.file); });
  ImGui::SameLine();
  if (ImGui::Button("save")) {
    if (ctx.attempt([&] { doc.save_sequence(s.file); })) ctx.log.info("saved " + s.file);
  }
}

}  // namespace welkin::editor
