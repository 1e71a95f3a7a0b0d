// The live view: the engine's tone-mapped output as an image sized to the panel (the application
// renders at the size asked for here), a fly camera (hold the right mouse button: mouse look,
// WASD, Q/E down/up, Shift faster, Ctrl slower, wheel scales speed) and a HUD of frame times.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>

#include "ui/panel_registry.h"
#include "ui/viewport_panel.h"
#include "welkin/gfx/camera.h"

namespace welkin::editor {

namespace {

ViewPose scene_camera_pose(const Camera& c) { return ViewPose{c.position_m, c.heading_deg, c.pitch_deg}; }

FlyInput read_fly_input(const ImGuiIO& io, double speed_multiplier) {
  auto axis = [](int plus, int minus) { return (ImGui::IsKeyDown(plus) ? 1.0 : 0.0) - (ImGui::IsKeyDown(minus) ? 1.0 : 0.0); };
  FlyInput in;
  in.forward = axis(GLFW_KEY_W, GLFW_KEY_S);
  in.right = axis(GLFW_KEY_D, GLFW_KEY_A);
  in.up = axis(GLFW_KEY_E, GLFW_KEY_Q);
  in.look_dx_px = io.MouseDelta.x;
  in.look_dy_px = io.MouseDelta.y;
  in.speed_multiplier = speed_multiplier * (io.KeyShift ? 5.0 : 1.0) * (io.KeyCtrl ? 0.2 : 1.0);
  in.dt_s = io.DeltaTime;
  return in;
}

}  // namespace

ViewPose current_view_pose(EditorContext& ctx) {
  Registry& reg = ctx.doc.world().registry();
  Entity camera_entity = reg.first<Camera>();
  if (ctx.viewport.look_through_scene_camera && !camera_entity.is_null()) return scene_camera_pose(*reg.get<Camera>(camera_entity));
  return ctx.viewport.pose;
}

ViewPose fly_view(EditorContext& ctx, const FlyInput& input) {
  ViewportState& vp = ctx.viewport;
  EditorDocument& doc = ctx.doc;
  ViewPose pose = current_view_pose(ctx);
  ViewPose next = fly(pose, input, vp.fly);
  Entity camera_entity = doc.world().registry().first<Camera>();
  if (!vp.look_through_scene_camera || camera_entity.is_null()) {
    vp.pose = next;
  } else if (!(next == pose)) {
    // Flying the scene camera is an edit like any other: one undo step per flight.
    EntityId id = doc.id_of(camera_entity);
    nlohmann::json c = doc.get_component(id, "core.Camera");
    c["position_m"] = {next.position_m.x, next.position_m.y, next.position_m.z};
    c["heading_deg"] = next.heading_deg;
    c["pitch_deg"] = next.pitch_deg;
    if (!ctx.attempt([&] { doc.set_component(id, "core.Camera", c, "Fly scene camera", true); })) return pose;
  }
  return next;
}

namespace {

void draw_toolbar(EditorContext& ctx, Entity camera_entity) {
  ViewportState& vp = ctx.viewport;
  EditorDocument& doc = ctx.doc;
  ImGui::Checkbox("look through scene camera", &vp.look_through_scene_camera);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Flying then moves the scene's core.Camera (undoable) instead of the editor's view");
  if (!camera_entity.is_null() && !vp.look_through_scene_camera) {
    ImGui::SameLine();
    if (ImGui::Button("view from scene camera")) vp.pose = scene_camera_pose(*doc.world().registry().get<Camera>(camera_entity));
    ImGui::SameLine();
    if (ImGui::Button("move scene camera here")) {
      EntityId id = doc.id_of(camera_entity);
      nlohmann::json cam = doc.get_component(id, "core.Camera");
      cam["position_m"] = {vp.pose.position_m.x, vp.pose.position_m.y, vp.pose.position_m.z};
      cam["heading_deg"] = vp.pose.heading_deg;
      cam["pitch_deg"] = vp.pose.pitch_deg;
      ctx.attempt([&] { doc.set_component(id, "core.Camera", cam, "Move scene camera to the view"); });
    }
  }
  ImGui::SameLine();
  ImGui::Checkbox("clock runs", &vp.clock_running);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The scene's clock: the clouds' wind drift, a time of day's time scale. Paused, a still view settles and costs little");
  ImGui::SameLine();
  if (ImGui::Button("screenshot")) ctx.screenshot_requests.push_back("screenshots/welkin-" + std::to_string(std::time(nullptr)) + ".png");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Writes the viewport to screenshots/ (PNG; the script verb also writes EXR)");
}

void draw_hud(EditorContext& ctx, ImVec2 at, const ViewPose& pose) {
  const FrameStats& st = ctx.stats;
  const ViewportState& vp = ctx.viewport;
  double speed = fly_speed_mps(pose.position_m.z, vp.fly) * vp.speed_multiplier;
  // What was cut: a moving frame renders a part of the viewport (the scale adapts to the budget).
  char cut[160];
  const int rw = st.last.rendered_width, rh = st.last.rendered_height;
  if (st.kept)
    std::snprintf(cut, sizeof cut, "settled: the last frame shown");
  else if (int64_t(rw) * rh < int64_t(vp.texture_width) * vp.texture_height)
    std::snprintf(cut, sizeof cut, "moving: rendered %dx%d (%.0f%%)%s", rw, rh, 100.0 * rw / std::max(vp.texture_width, 1),
                  vp.moving_scale.budget_ms > 0 ? ", sized to the budget" : "");
  else
    std::snprintf(cut, sizeof cut, "whole frame");
  char text[480];
  std::snprintf(text, sizeof text,
                "%.2f ms  %.0f fps   GPU %.3f ms\n%dx%d   %s   clock %s\nalt %.1f m   speed %.3g m/s\n%s",
                st.cpu_frame_ms, st.cpu_frame_ms > 0 ? 1000.0 / st.cpu_frame_ms : 0.0, st.gpu_total_ms, vp.texture_width,
                vp.texture_height, cut, vp.clock_running ? "runs" : "paused", pose.position_m.z, speed,
                vp.flying ? "flying: WASD, Q/E, Shift/Ctrl, wheel" : "hold right mouse to fly");
  ImDrawList* draw = ImGui::GetWindowDrawList();
  ImVec2 size = ImGui::CalcTextSize(text);
  draw->AddRectFilled(ImVec2(at.x + 4, at.y + 4), ImVec2(at.x + 12 + size.x, at.y + 12 + size.y), IM_COL32(0, 0, 0, 140), 4.0f);
  draw->AddText(ImVec2(at.x + 8, at.y + 8), IM_COL32(255, 255, 255, 230), text);
}

}  // namespace

void draw_viewport_panel(EditorContext& ctx) {
  ViewportState& vp = ctx.viewport;
  EditorDocument& doc = ctx.doc;
  Registry& reg = doc.world().registry();
  Entity camera_entity = reg.first<Camera>();
  draw_toolbar(ctx, camera_entity);

  ImVec2 avail = ImGui::GetContentRegionAvail();
  vp.render_width = std::max(1, int(avail.x));
  vp.render_height = std::max(1, int(avail.y));
  if (camera_entity.is_null()) {
    ImGui::TextWrapped("The scene has no core.Camera, so there is nothing to render.");
    if (ImGui::Button("add a camera"))
      ctx.attempt([&] { doc.add_entity("camera", nlohmann::json{{"core.Camera", nlohmann::json::object()}}); });
    return;
  }

  ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("view", ImVec2(float(vp.render_width), float(vp.render_height)),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  bool hovered = ImGui::IsItemHovered();
  vp.flying = ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Right);
  end_map_stroke(ctx);
  if (ImGui::IsItemActive() && !vp.flying && ImGui::IsMouseDown(ImGuiMouseButton_Left) && ctx.map_brush.viewport_target) {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    paint_in_viewport(ctx, glm::dvec2(mouse.x - origin.x, mouse.y - origin.y));
  }
  if (vp.texture) {
    // GL rows go bottom-up: flip v.
    ImGui::GetWindowDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(vp.texture)), origin,
                                         ImVec2(origin.x + float(vp.texture_width), origin.y + float(vp.texture_height)),
                                         ImVec2(0, 1), ImVec2(1, 0));
  }
  if (!vp.render_error.empty()) {
    ImGui::SetCursorScreenPos(ImVec2(origin.x + 8, origin.y + 80));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("render failed: %s", vp.render_error.c_str());
    ImGui::PopStyleColor();
  }

  const ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0.0f) vp.speed_multiplier = std::clamp(vp.speed_multiplier * std::pow(1.25, io.MouseWheel), 1e-3, 1e3);
  ViewPose pose = vp.flying ? fly_view(ctx, read_fly_input(io, vp.speed_multiplier)) : current_view_pose(ctx);
  if (vp.flying) ImGui::SetMouseCursor(ImGuiMouseCursor_None);
  draw_hud(ctx, origin, pose);
}

}  // namespace welkin::editor
