#include "ui/field_inspector.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cfloat>
#include <cmath>
#include <optional>

#include "model/reflected_object.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

// How a number is edited: a slider over a modest range, a logarithmic slider over a wide positive
// one (luminance 0..1e9), a drag whose speed follows the value's magnitude otherwise (positions).
struct NumericWidget {
  enum class Kind { slider, log_slider, drag } kind = Kind::drag;
  double min = -DBL_MAX, max = DBL_MAX;
  float drag_speed = 0.01f;
};

NumericWidget numeric_widget(const FieldDesc& f, double magnitude) {
  NumericWidget w;
  if (f.min) w.min = *f.min;
  if (f.max) w.max = *f.max;
  if (f.min && f.max && *f.max - *f.min <= 1000) w.kind = NumericWidget::Kind::slider;
  else if (f.min && f.max && *f.min >= 0) w.kind = NumericWidget::Kind::log_slider;
  w.drag_speed = float(std::max(std::abs(magnitude) * 0.005, f.kind == FieldKind::integer ? 0.2 : 1e-3));
  return w;
}

std::string field_label(const FieldDesc& f) { return f.unit.empty() ? f.name : f.name + " [" + f.unit + "]"; }

std::string range_text(const FieldDesc& f) {
  if (!f.min && !f.max) return {};
  char buf[96];
  std::snprintf(buf, sizeof buf, "range [%g, %g]%s%s", f.min ? *f.min : -INFINITY, f.max ? *f.max : INFINITY,
                f.unit.empty() ? "" : " ", f.unit.c_str());
  return buf;
}

class FieldDrawer {
 public:
  FieldDrawer(EditorContext& ctx, EntityId entity, const TypeDesc& type) : ctx_(ctx), entity_(entity), type_(type) {}

  void draw_object(const TypeDesc& t, void* object, const void* defaults, const std::string& prefix) {
    for (const FieldDesc& f : t.fields) {
      ImGui::PushID(f.name.c_str());
      draw_field(f, f.ptr(object), defaults ? f.ptr(defaults) : nullptr, prefix + f.name);
      ImGui::PopID();
    }
  }

  // Applies the one change this frame's widgets made (at most one item is active at a time).
  void commit() {
    if (edit_) {
      bool ok = ctx_.attempt([&] { ctx_.doc.set_field(entity_, type_.name, edit_->path, edit_->value, edit_->continuous); });
      if (!ok) ctx_.doc.end_continuous_edit();
    }
    if (seal_) ctx_.doc.end_continuous_edit();
  }

 private:
  struct PendingEdit {
    std::string path;
    json value;
    bool continuous = false;
  };

  void changed(const FieldDesc& f, const void* value, const std::string& path, bool continuous) {
    edit_ = PendingEdit{path, field_to_json(f, value), continuous};
  }

  // Tooltip, context menu and release detection shared by every leaf widget.
  void decorate(const FieldDesc& f, const void* defaults, const void* value, const std::string& path) {
    if (ImGui::IsItemDeactivatedAfterEdit()) seal_ = true;
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::TextDisabled("%s/%s  (%s)", type_.name.c_str(), path.c_str(), field_kind_name(f.kind));
      if (!f.tooltip.empty()) ImGui::TextUnformatted(f.tooltip.c_str());
      if (std::string r = range_text(f); !r.empty()) ImGui::TextUnformatted(r.c_str());
      ImGui::EndTooltip();
    }
    if (ImGui::BeginPopupContextItem("field menu")) {
      if (ImGui::MenuItem("Reset to default", nullptr, false, defaults != nullptr))
        edit_ = PendingEdit{path, field_to_json(f, defaults), false};
      std::string target = type_.name + "/" + path;
      bool keyable = f.kind != FieldKind::array && f.kind != FieldKind::object;  // sequences key values, not structs
      if (ImGui::MenuItem("Key at playhead", nullptr, false, keyable)) {
        std::string entity_name;
        if (const Name* n = ctx_.doc.world().registry().get<Name>(ctx_.doc.entity(entity_))) entity_name = n->value;
        double t = ctx_.timeline.playhead_s;
        json v = field_to_json(f, value);
        ctx_.attempt([&] { ctx_.doc.set_sequence(with_key(ctx_.doc.sequence(), entity_name, target, t, v), "Key " + target); });
      }
      if (ImGui::MenuItem("Copy path")) ImGui::SetClipboardText(target.c_str());
      ImGui::EndPopup();
    }
  }

  bool numeric(const char* label, ImGuiDataType type, void* data, int n, const FieldDesc& f, double magnitude) {
    NumericWidget w = numeric_widget(f, magnitude);
    bool is_double = type == ImGuiDataType_Double;
    bool is_int = type == ImGuiDataType_S32;
    // Bounds in the widget's own type.
    float fmin = float(std::max(w.min, -double(FLT_MAX))), fmax = float(std::min(w.max, double(FLT_MAX)));
    int imin = int(std::max(w.min, double(INT32_MIN))), imax = int(std::min(w.max, double(INT32_MAX)));
    const void* pmin = is_double ? static_cast<const void*>(&w.min) : is_int ? static_cast<const void*>(&imin) : &fmin;
    const void* pmax = is_double ? static_cast<const void*>(&w.max) : is_int ? static_cast<const void*>(&imax) : &fmax;
    const char* format = is_int ? "%d" : "%.6g";
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
    switch (w.kind) {
      case NumericWidget::Kind::slider: return ImGui::SliderScalarN(label, type, data, n, pmin, pmax, format, flags);
      case NumericWidget::Kind::log_slider:
        return ImGui::SliderScalarN(label, type, data, n, pmin, pmax, format, flags | ImGuiSliderFlags_Logarithmic);
      case NumericWidget::Kind::drag:
        return ImGui::DragScalarN(label, type, data, n, w.drag_speed, f.min ? pmin : nullptr, f.max ? pmax : nullptr, format, flags);
    }
    return false;
  }

  void draw_field(const FieldDesc& f, void* value, const void* defaults, const std::string& path) {
    std::string label = field_label(f);
    const char* l = label.c_str();
    switch (f.kind) {
      case FieldKind::boolean: {
        if (ImGui::Checkbox(l, static_cast<bool*>(value))) changed(f, value, path, false);
        break;
      }
      case FieldKind::integer: {
        int* v = static_cast<int*>(value);
        if (numeric(l, ImGuiDataType_S32, v, 1, f, *v)) changed(f, value, path, true);
        break;
      }
      case FieldKind::f32: {
        float* v = static_cast<float*>(value);
        if (numeric(l, ImGuiDataType_Float, v, 1, f, *v)) changed(f, value, path, true);
        break;
      }
      case FieldKind::f64: {
        double* v = static_cast<double*>(value);
        if (numeric(l, ImGuiDataType_Double, v, 1, f, *v)) changed(f, value, path, true);
        break;
      }
      case FieldKind::vec2:
      case FieldKind::vec3:
      case FieldKind::vec4: {
        float* v = static_cast<float*>(value);
        int n = field_kind_arity(f.kind);
        double magnitude = 0;
        for (int i = 0; i < n; ++i) magnitude = std::max(magnitude, double(std::abs(v[i])));
        if (numeric(l, ImGuiDataType_Float, v, n, f, magnitude)) changed(f, value, path, true);
        break;
      }
      case FieldKind::dvec3: {
        double* v = &(*static_cast<glm::dvec3*>(value))[0];
        double magnitude = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
        if (numeric(l, ImGuiDataType_Double, v, 3, f, magnitude)) changed(f, value, path, true);
        break;
      }
      case FieldKind::color: {
        // Linear RGB; values above 1 (radiance-like colours) get the HDR picker.
        ImGuiColorEditFlags flags = ImGuiColorEditFlags_Float;
        if (!f.max || *f.max > 1.0) flags |= ImGuiColorEditFlags_HDR;
        if (ImGui::ColorEdit3(l, &(*static_cast<glm::vec3*>(value))[0], flags)) changed(f, value, path, true);
        break;
      }
      case FieldKind::enumeration: {
        int* v = static_cast<int*>(value);
        const EnumValue* current = f.enum_by_value(*v);
        if (ImGui::BeginCombo(l, current ? current->name.c_str() : "?")) {
          for (const EnumValue& e : f.enum_values) {
            if (ImGui::Selectable(e.name.c_str(), e.value == *v) && e.value != *v) {
              *v = e.value;
              changed(f, value, path, false);
            }
          }
          ImGui::EndCombo();
        }
        break;
      }
      case FieldKind::string: {
        if (ImGui::InputText(l, static_cast<std::string*>(value))) changed(f, value, path, true);
        break;
      }
      case FieldKind::object: {
        bool open = ImGui::TreeNodeEx(l, ImGuiTreeNodeFlags_DefaultOpen);
        decorate(f, defaults, value, path);
        if (open) {
          draw_object(*f.element, value, defaults, path + "/");
          ImGui::TreePop();
        }
        return;
      }
      case FieldKind::array: {
        draw_array(f, value, defaults, path, l);
        return;
      }
    }
    decorate(f, defaults, value, path);
  }

  void draw_array(const FieldDesc& f, void* value, const void* defaults, const std::string& path, const char* label) {
    size_t n = f.array.size(value);
    std::string title = std::string(label) + " [" + std::to_string(n) + "]";
    bool open = ImGui::TreeNodeEx(title.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    decorate(f, defaults, value, path);
    if (!open) return;
    const void* element_defaults = f.element->defaults.get();
    std::optional<size_t> remove, move_up;  // move_up: element i swaps with i - 1
    for (size_t i = 0; i < n; ++i) {
      ImGui::PushID(int(i));
      std::string element = path + "/" + std::to_string(i);
      bool element_open = ImGui::TreeNodeEx(element.c_str(), ImGuiTreeNodeFlags_DefaultOpen, "%s %zu", f.element->name.c_str(), i);
      ImGui::SameLine();
      if (ImGui::SmallButton("remove")) remove = i;
      // Order matters to what draws first and to sequences' paths: elements move one place at a time.
      ImGui::SameLine();
      ImGui::BeginDisabled(i == 0);
      if (ImGui::SmallButton("up")) move_up = i;
      ImGui::EndDisabled();
      ImGui::SameLine();
      ImGui::BeginDisabled(i + 1 == n);
      if (ImGui::SmallButton("down")) move_up = i + 1;
      ImGui::EndDisabled();
      if (element_open) {
        draw_object(*f.element, f.array.at(value, i), element_defaults, element + "/");
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    json whole = field_to_json(f, value);
    if (remove) {
      whole.erase(*remove);
      edit_ = PendingEdit{path, whole, false};
    } else if (move_up) {
      std::swap(whole[*move_up], whole[*move_up - 1]);
      edit_ = PendingEdit{path, whole, false};
    }
    ImGui::BeginDisabled(n >= f.max_count);
    if (ImGui::SmallButton("add")) {
      whole.push_back(object_to_json(*f.element, element_defaults));
      edit_ = PendingEdit{path, whole, false};
    }
    ImGui::EndDisabled();
    if (n >= f.max_count) {
      ImGui::SameLine();
      ImGui::TextDisabled("(at most %zu)", f.max_count);
    }
    ImGui::TreePop();
  }

  EditorContext& ctx_;
  EntityId entity_;
  const TypeDesc& type_;
  std::optional<PendingEdit> edit_;
  bool seal_ = false;
};

}  // namespace

void draw_component_fields(EditorContext& ctx, EntityId entity, const TypeDesc& type) {
  const void* live = ctx.doc.component_data(entity, type);
  if (!live) return;
  // Widgets edit a copy; the change goes back through the document (validated, undoable).
  ReflectedObject copy(type, live);
  FieldDrawer drawer(ctx, entity, type);
  ImGui::PushID(type.name.c_str());
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 11);
  drawer.draw_object(type, copy.get(), type.defaults.get(), "");
  ImGui::PopItemWidth();
  ImGui::PopID();
  drawer.commit();
}

}  // namespace welkin::editor
