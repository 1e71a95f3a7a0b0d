// The preset browser: every module's preset files, grouped by module and, within a module, by
// sub-folder (the clouds' genera). Apply, blend two (A/B and a slider), save over, save as, rename,
// revert to the file, and see which fields differ from it. A preset of one element of an array (a
// cloud layer of a genus) is added as a new element or applied over a chosen one. A file that fails
// to load is listed in red with its error and is never written.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>

#include "model/preset_actions.h"
#include "ui/panel_registry.h"

namespace welkin::editor {

namespace {

struct PresetKey {
  std::string module, name;
  bool empty() const { return name.empty(); }
  bool is(const PresetFile& p) const { return p.module == module && p.name == name; }
};

// Presets are addressed by (module, name): a rescan replaces the PresetFile objects.
struct PresetPanelState {
  PresetKey blend_a, blend_b;
  float blend_t = 0.5f;
  std::string save_as_name = "my-preset";
  std::string save_as_component;
  std::string rename_to;
  std::string pending_overwrite;  // a save-as target that exists, awaiting confirmation
  int element = 0;                // which element an element preset is applied to, saved from, compared with
};

const PresetFile* lookup(PresetLibrary& presets, const PresetKey& key) {
  return key.empty() ? nullptr : presets.find(key.module, key.name);
}

// Where a preset applies: the selected entity when it has the component, else the first with it,
// else the selected entity (which gains the component).
EntityId preset_target(EditorDocument& doc, const std::string& component) {
  EntityId id = doc.entity_with(component);
  return id != kNoEntity ? id : doc.selected();
}

void select(EditorContext& ctx, const std::string& module, const std::string& name) {
  ctx.preset_browser.selected_module = module;
  ctx.preset_browser.selected_name = name;
}

bool is_selected(const EditorContext& ctx, const PresetFile& p) {
  return ctx.preset_browser.selected_module == p.module && ctx.preset_browser.selected_name == p.name;
}

void draw_rename_popup(EditorContext& ctx, PresetPanelState& s, const PresetFile& p) {
  if (!ImGui::BeginPopup("rename preset")) return;
  ImGui::InputText("new name", &s.rename_to);
  if (ImGui::Button("rename")) {
    PresetFile copy = p;
    if (ctx.attempt([&] { ctx.presets.rename(copy, s.rename_to); }))
      select(ctx, copy.module, copy.folder.empty() ? s.rename_to : copy.folder + "/" + s.rename_to);
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

// A preset of one element of an array (a cloud layer): added as a new element, or applied over,
// saved from and compared with the element chosen.
void draw_element_details(EditorContext& ctx, PresetPanelState& s, const PresetFile& p, EntityId target) {
  if (ImGui::Button("add as a new element"))
    ctx.attempt([&] { apply_preset(ctx.doc, ctx.presets, p, target); });
  const int count = int(element_count(ctx.doc, p, target));
  if (count == 0) return;
  s.element = std::clamp(s.element, 0, count - 1);
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
  ImGui::InputInt(p.element_field.c_str(), &s.element);
  s.element = std::clamp(s.element, 0, count - 1);
  const size_t index = size_t(s.element);
  ImGui::SameLine();
  if (ImGui::Button("apply to it"))
    ctx.attempt([&] { apply_preset_to_element(ctx.doc, ctx.presets, p, target, index); });
  ImGui::SameLine();
  if (ImGui::Button("save it over file")) ImGui::OpenPopup("confirm save");
  ImGui::SameLine();
  if (ImGui::Button("rename")) {
    s.rename_to = p.file.stem().string();
    ImGui::OpenPopup("rename preset");
  }
  if (ImGui::BeginPopup("confirm save")) {
    ImGui::Text("Write %s/%zu over %s?", p.element_field.c_str(), index, p.file.filename().string().c_str());
    if (ImGui::Button("write")) {
      PresetFile copy = p;
      if (ctx.attempt([&] { save_preset_element(ctx.doc, ctx.presets, copy, target, index); }))
        ctx.log.info("saved " + copy.file.string());
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;  // the save may have rescanned: `p` is stale now
  }
  if (ImGui::IsPopupOpen("rename preset")) return draw_rename_popup(ctx, s, p);
  auto differences = preset_element_differences(ctx.doc, ctx.presets, p, target, index);
  if (differences.empty())
    ImGui::TextDisabled("%s/%zu matches the file", p.element_field.c_str(), index);
  else
    ImGui::Text("%s/%zu differs from the file in %zu field(s)", p.element_field.c_str(), index,
                differences.size());
  for (const auto& f : differences) ImGui::BulletText("%s", f.c_str());
}

void draw_details(EditorContext& ctx, PresetPanelState& s, const PresetFile& p) {
  ImGui::TextDisabled("%s", p.file.string().c_str());
  if (!p.ok()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("Does not load: %s", format_error(*p.error).c_str());
    ImGui::PopStyleColor();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("The file is left untouched; fix it in a text editor, then rescan.");
    ImGui::PopStyleColor();
    return;
  }
  EntityId target = preset_target(ctx.doc, p.component);
  ImGui::Text("%s  ->  %s", p.target().c_str(),
              target == kNoEntity ? "(no entity)" : ctx.doc.display_name(target).c_str());
  if (target == kNoEntity) return;
  if (p.is_element()) return draw_element_details(ctx, s, p, target);
  if (ImGui::Button("apply")) ctx.attempt([&] { apply_preset(ctx.doc, ctx.presets, p, target); });
  ImGui::SameLine();
  if (ImGui::Button("revert to file")) ctx.attempt([&] { revert_to_preset_file(ctx.doc, ctx.presets, p, target); });
  ImGui::SameLine();
  bool has_component = !ctx.doc.get_component(target, p.component).is_null();
  ImGui::BeginDisabled(!has_component);
  if (ImGui::Button("save over file")) ImGui::OpenPopup("confirm save");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("rename")) {
    s.rename_to = p.file.stem().string();
    ImGui::OpenPopup("rename preset");
  }
  if (ImGui::BeginPopup("confirm save")) {
    ImGui::Text("Write %s's %s over %s?", ctx.doc.display_name(target).c_str(), p.component.c_str(), p.file.filename().string().c_str());
    if (ImGui::Button("write")) {
      PresetFile copy = p;
      if (ctx.attempt([&] { save_preset(ctx.doc, ctx.presets, copy, target); })) ctx.log.info("saved " + copy.file.string());
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;  // the save may have rescanned: `p` is stale now
  }
  if (ImGui::IsPopupOpen("rename preset"))
    return draw_rename_popup(ctx, s, p);  // may rescan: `p` is stale after
  if (!has_component) return;
  auto differences = preset_differences(ctx.doc, ctx.presets, p, target);
  if (differences.empty()) {
    ImGui::TextDisabled("matches the file");
  } else {
    ImGui::Text("%zu field(s) differ from the file:", differences.size());
    for (const auto& f : differences) {
      ImGui::BulletText("%s", f.c_str());
      if (ImGui::IsItemHovered()) {
        std::string now = ctx.doc.get_field(target, p.component, f).dump();
        std::string file = ctx.presets.complete_value(p).value(nlohmann::json::json_pointer("/" + f), nlohmann::json()).dump();
        ImGui::SetTooltip("now:  %s\nfile: %s", now.c_str(), file.c_str());
      }
    }
  }
}

void draw_blend(EditorContext& ctx, PresetPanelState& s) {
  const PresetFile* a = lookup(ctx.presets, s.blend_a);
  const PresetFile* b = lookup(ctx.presets, s.blend_b);
  ImGui::Text("A: %s   B: %s", a ? a->name.c_str() : "-", b ? b->name.c_str() : "-");
  bool ready =
      a && b && a->ok() && b->ok() && a->component == b->component && !a->is_element() && !b->is_element();
  if (a && b && a->component != b->component) ImGui::TextDisabled("A and B set different components");
  if ((a && a->is_element()) || (b && b->is_element())) ImGui::TextDisabled("only whole components blend");
  ImGui::BeginDisabled(!ready);
  bool moved = ImGui::SliderFloat("blend A -> B", &s.blend_t, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  bool released = ImGui::IsItemDeactivatedAfterEdit();
  ImGui::EndDisabled();
  if (ready && moved) {
    EntityId target = preset_target(ctx.doc, a->component);
    if (target != kNoEntity) ctx.attempt([&] { blend_presets(ctx.doc, ctx.presets, *a, *b, s.blend_t, target, true); });
  }
  if (released) ctx.doc.end_continuous_edit();  // the whole drag is one undo step
}

void draw_save_as(EditorContext& ctx, PresetPanelState& s) {
  EntityId selected = ctx.doc.selected();
  if (selected == kNoEntity) {
    ImGui::TextDisabled("Select an entity to save one of its components as a preset.");
    return;
  }
  if (ImGui::BeginCombo("component", s.save_as_component.empty() ? "choose..." : s.save_as_component.c_str())) {
    for (const TypeDesc* t : ctx.doc.components_of(selected))
      if (t->name != "core.Name" && ImGui::Selectable(t->name.c_str(), t->name == s.save_as_component)) s.save_as_component = t->name;
    ImGui::EndCombo();
  }
  ImGui::InputText("preset name", &s.save_as_name);
  const ModuleManifest* provider = s.save_as_component.empty() ? nullptr : ctx.doc.world().modules().provider_of(s.save_as_component);
  std::filesystem::path file;
  if (provider) {
    try {
      file = ctx.presets.folder_of(provider->name) / (s.save_as_name + ".json");
    } catch (const std::exception&) {
      ImGui::TextDisabled("module %s has no preset folder", provider->name.c_str());
    }
  }
  if (!file.empty()) ImGui::TextDisabled("-> %s", file.string().c_str());
  bool valid_name = !s.save_as_name.empty() && s.save_as_name.find_first_of("/\\") == std::string::npos && s.save_as_name[0] != '.';
  ImGui::BeginDisabled(file.empty() || !valid_name || ctx.doc.get_component(selected, s.save_as_component).is_null());
  if (ImGui::Button("save as")) {
    std::error_code ec;
    if (std::filesystem::exists(file, ec)) {
      s.pending_overwrite = file.string();
      ImGui::OpenPopup("confirm overwrite");
    } else if (ctx.attempt([&] { save_preset_as(ctx.doc, ctx.presets, s.save_as_component, selected, file); })) {
      ctx.log.info("saved " + file.string());
      select(ctx, provider->name, s.save_as_name);
    }
  }
  ImGui::EndDisabled();
  if (ImGui::BeginPopup("confirm overwrite")) {
    ImGui::Text("%s exists. Replace it?", s.pending_overwrite.c_str());
    if (ImGui::Button("replace")) {
      std::string target = s.pending_overwrite;
      if (ctx.attempt([&] { save_preset_as(ctx.doc, ctx.presets, s.save_as_component, selected, target); }))
        ctx.log.info("saved " + target);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

void draw_row(EditorContext& ctx, PresetPanelState& s, const PresetFile& p) {
  ImGui::PushID(p.name.c_str());
  if (ImGui::SmallButton(s.blend_a.is(p) ? "[A]" : " A ")) s.blend_a = {p.module, p.name};
  ImGui::SameLine();
  if (ImGui::SmallButton(s.blend_b.is(p) ? "[B]" : " B ")) s.blend_b = {p.module, p.name};
  ImGui::SameLine();
  if (!p.ok()) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
  const std::string leaf = p.folder.empty() ? p.name : p.name.substr(p.folder.size() + 1);
  std::string label = p.ok() ? leaf + "  (" + p.target() + ")" : leaf + "  (does not load)";
  if (ImGui::Selectable(label.c_str(), is_selected(ctx, p), ImGuiSelectableFlags_AllowDoubleClick)) {
    select(ctx, p.module, p.name);
    if (ImGui::IsMouseDoubleClicked(0) && p.ok()) {
      EntityId target = preset_target(ctx.doc, p.component);
      if (target != kNoEntity) ctx.attempt([&] { apply_preset(ctx.doc, ctx.presets, p, target); });
    }
  }
  if (!p.ok()) {
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", format_error(*p.error).c_str());
  }
  ImGui::PopID();
}

// One folder's presets: those at its top, then each sub-folder as a node of its own.
void draw_folder(EditorContext& ctx, PresetPanelState& s, const PresetFolder& folder) {
  const std::vector<const PresetFile*> files = ctx.presets.presets_in(folder);
  std::string open_folder;
  bool open = true;
  for (const PresetFile* p : files) {
    if (p->folder != open_folder) {
      if (!open_folder.empty() && open) ImGui::TreePop();
      open_folder = p->folder;
      open = ImGui::TreeNodeEx(p->folder.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    }
    if (open) draw_row(ctx, s, *p);
  }
  if (!open_folder.empty() && open) ImGui::TreePop();
}

}  // namespace

void draw_preset_panel(EditorContext& ctx) {
  static PresetPanelState s;
  if (ImGui::Button("rescan")) ctx.presets.rescan();
  ImGui::SameLine();
  ImGui::TextDisabled("%zu preset files", ctx.presets.presets().size());

  // The list, grouped by module and sub-folder; A and B pick the blend ends.
  ImGui::BeginChild("preset list", ImVec2(0, ImGui::GetContentRegionAvail().y * 0.45f), true);
  for (const PresetFolder& folder : ctx.presets.folders()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(folder.dir, ec)) continue;  // a module without presets (yet)
    ImGui::PushID(folder.dir.string().c_str());
    bool open = ImGui::TreeNodeEx(folder.module.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", folder.dir.string().c_str());
    if (open) {
      draw_folder(ctx, s, folder);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  ImGui::EndChild();

  if (const PresetFile* p = lookup(ctx.presets, {ctx.preset_browser.selected_module, ctx.preset_browser.selected_name})) {
    ImGui::Separator();
    draw_details(ctx, s, *p);
  }
  ImGui::Separator();
  ImGui::TextUnformatted("Blend");
  draw_blend(ctx, s);
  ImGui::Separator();
  ImGui::TextUnformatted("Save as");
  draw_save_as(ctx, s);
}

}  // namespace welkin::editor
