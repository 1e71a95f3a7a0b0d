// A map a module declares (a "map" panel in its editor/panels.json): the map as an image with the
// camera on it, a brush to paint it there or in the viewport, and a new map beside the scene. Every
// stroke is one undo step (model/map_painting.h).
#include <epoxy/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/panel_registry.h"
#include "ui/viewport_panel.h"
#include "welkin/gfx/renderer.h"

namespace welkin::editor {

namespace {

// Keeps the panel's grey texture in step with the map (a stroke bumps its revision).
unsigned map_texture(MapBrushState& st, const std::string& file, const PaintedMap& map) {
  if (st.texture && st.texture_file == file && st.texture_revision == map.revision) return st.texture;
  if (st.texture) glDeleteTextures(1, &st.texture);
  glCreateTextures(GL_TEXTURE_2D, 1, &st.texture);
  glTextureStorage2D(st.texture, 1, GL_R8, map.side, map.side);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(st.texture, 0, 0, 0, map.side, map.side, GL_RED, GL_UNSIGNED_BYTE, map.texels.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  const GLint grey[4] = {GL_RED, GL_RED, GL_RED, GL_ONE};
  glTextureParameteriv(st.texture, GL_TEXTURE_SWIZZLE_RGBA, grey);
  glTextureParameteri(st.texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  st.texture_file = file;
  st.texture_revision = map.revision;
  return st.texture;
}

void draw_brush_controls(MapBrushState& st) {
  int mode = int(st.brush.mode);
  ImGui::RadioButton("add cloud", &mode, int(BrushMode::add));
  ImGui::SameLine();
  ImGui::RadioButton("clear", &mode, int(BrushMode::clear));
  ImGui::SameLine();
  ImGui::RadioButton("reset", &mode, int(BrushMode::reset));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back toward the layers' own coverage (texel 128)");
  st.brush.mode = BrushMode(mode);
  const double min_radius = 10.0, max_radius = 1e6, min_strength = 0.0, max_strength = 1.0;
  ImGui::SliderScalar("radius (m)", ImGuiDataType_Double, &st.brush.radius_m, &min_radius, &max_radius, "%.0f",
                      ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  ImGui::SliderScalar("strength", ImGuiDataType_Double, &st.brush.strength, &min_strength, &max_strength, "%.2f",
                      ImGuiSliderFlags_AlwaysClamp);
}

}  // namespace

void draw_map_panel(EditorContext& ctx, const MapFieldSpec& spec) {
  MapBrushState& st = ctx.map_brush;
  end_map_stroke(ctx);
  MapTarget target;
  try {
    target = find_map(ctx.doc, spec);
  } catch (const std::exception& e) {
    ImGui::TextWrapped("%s", e.what());
    if (ctx.doc.entity_with(spec.component) == kNoEntity && ImGui::Button("add to a new entity"))
      ctx.attempt([&] { ctx.doc.add_entity(spec.component, nlohmann::json{{spec.component, nlohmann::json::object()}}); });
    return;
  }
  ImGui::TextDisabled("%s/%s on '%s'", spec.component.c_str(), spec.file_field.c_str(), ctx.doc.display_name(target.entity).c_str());
  draw_brush_controls(st);

  if (target.file.empty()) {
    ImGui::TextWrapped("No map yet: a new one starts neutral (the layers' own coverage) and is written beside the scene when it is saved.");
    ImGui::SliderInt("side (texels)", &st.new_map_side, 16, kMaxPaintedMapSide, "%d", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    ImGui::BeginDisabled(ctx.doc.scene_path().empty());
    if (ImGui::Button("new map beside the scene")) ctx.attempt([&] { new_map(ctx.doc, spec, st.new_map_side); });
    ImGui::EndDisabled();
    if (ctx.doc.scene_path().empty()) ImGui::TextDisabled("Save the scene first: the map goes beside it.");
    return;
  }

  const PaintedMap* map = nullptr;
  try {
    map = &ctx.doc.world().resource<PaintedMaps>().get(target.file);
  } catch (const std::exception& e) {
    ImGui::TextWrapped("%s", e.what());
    return;
  }
  bool in_viewport = st.viewport_target == spec;
  if (ImGui::Checkbox("paint in the viewport", &in_viewport)) st.viewport_target = in_viewport ? std::optional(spec) : std::nullopt;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Left-drag in the viewport paints where the view meets the altitude below");
  if (in_viewport) {
    const double lo = 0.0, hi = 20000.0;
    ImGui::SliderScalar("at altitude (m)", ImGuiDataType_Double, &st.altitude_m, &lo, &hi, "%.0f");
  }
  ImGui::Text("%s  (%d x %d, %.1f km)%s", target.file.c_str(), map->side, map->side, target.frame.size_m / 1000.0, map->unsaved ? "  unsaved" : "");

  // The map, north up; drag on it to paint.
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float side = std::max(64.0f, std::min(avail.x, avail.y - 8.0f));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("map", ImVec2(side, side));
  const bool hovered = ImGui::IsItemHovered(), pressed = ImGui::IsItemActive();  // pressed: the drag began here
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(map_texture(st, target.file, *map))), origin,
                 ImVec2(origin.x + side, origin.y + side));
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (hovered || pressed)
    draw->AddCircle(mouse, float(st.brush.radius_m / target.frame.size_m) * side, IM_COL32(255, 200, 60, 220), 48, 1.5f);
  if (pressed && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    const glm::dvec2 uv((mouse.x - origin.x) / side, (mouse.y - origin.y) / side);
    st.stroking = ctx.attempt([&] { paint_at(ctx.doc, spec, target.frame.ground_point(uv), st.brush, true); });
  }
  // The view on the map: where it is and where it looks.
  const ViewPose pose = current_view_pose(ctx);
  const glm::dvec2 at = target.frame.uv(pose.position_m);
  if (at.x >= 0.0 && at.x <= 1.0 && at.y >= 0.0 && at.y <= 1.0) {
    const ImVec2 p(origin.x + float(at.x) * side, origin.y + float(at.y) * side);
    const double h = glm::radians(double(pose.heading_deg));  // clockwise from north; the image's y points south
    draw->AddCircleFilled(p, 4.0f, IM_COL32(80, 200, 255, 255));
    draw->AddLine(p, ImVec2(p.x + 14.0f * float(std::sin(h)), p.y - 14.0f * float(std::cos(h))), IM_COL32(80, 200, 255, 255), 2.0f);
  }
}

// Left-drag in the viewport with a map's brush on: the stamp goes where the view ray meets the
// brush's altitude (the map reads along the planet's radius, so that is the column painted).
void paint_in_viewport(EditorContext& ctx, glm::dvec2 pixel) {
  MapBrushState& st = ctx.map_brush;
  RenderContext* rc = ctx.doc.world().find_resource<RenderContext>();
  if (!st.viewport_target || !rc) return;
  MapTarget target;
  if (!ctx.attempt([&] { target = find_map(ctx.doc, *st.viewport_target); }) || target.file.empty()) return;
  // The last frame's view may be smaller than the viewport (rendered while moving): its own pixels.
  const ViewportState& vp = ctx.viewport;
  if (vp.texture_width > 0 && vp.texture_height > 0)
    pixel *= glm::dvec2(double(rc->view.width) / vp.texture_width, double(rc->view.height) / vp.texture_height);
  const glm::vec3 dir = pixel_direction(rc->view, pixel.x, pixel.y);
  if (auto hit = ray_at_altitude(target.frame, rc->view.camera_position_m, glm::dvec3(dir), st.altitude_m))
    st.stroking = ctx.attempt([&] { paint_at(ctx.doc, *st.viewport_target, *hit, st.brush, true); });
}

void end_map_stroke(EditorContext& ctx) {
  if (!ctx.map_brush.stroking || ImGui::IsMouseDown(ImGuiMouseButton_Left)) return;
  ctx.doc.end_continuous_edit();
  ctx.map_brush.stroking = false;
}

}  // namespace welkin::editor
