#include "model/value_blend.h"

#include <cmath>

namespace welkin::editor {

using nlohmann::json;

namespace {

json lerp_number(FieldKind kind, const json& a, const json& b, double t) {
  if (!a.is_number() || !b.is_number()) return t < 0.5 ? a : b;
  double v = std::lerp(a.get<double>(), b.get<double>(), t);
  if (kind == FieldKind::integer) return json(std::llround(v));
  return json(v);
}

bool is_numeric(FieldKind kind) {
  switch (kind) {
    case FieldKind::integer:
    case FieldKind::f32:
    case FieldKind::f64:
    case FieldKind::vec2:
    case FieldKind::vec3:
    case FieldKind::vec4:
    case FieldKind::dvec3:
    case FieldKind::color: return true;
    default: return false;
  }
}

void collect_differences(const TypeDesc& type, const json& a, const json& b, const std::string& prefix,
                         std::vector<std::string>& out) {
  for (const FieldDesc& f : type.fields) {
    std::string path = prefix + f.name;
    auto ia = a.find(f.name), ib = b.find(f.name);
    bool has_a = ia != a.end(), has_b = ib != b.end();
    if (!has_a || !has_b) {
      if (has_a != has_b) out.push_back(path);
      continue;
    }
    if (f.kind == FieldKind::object && ia->is_object() && ib->is_object()) {
      collect_differences(*f.element, *ia, *ib, path + "/", out);
    } else if (f.kind == FieldKind::array && ia->is_array() && ib->is_array() && ia->size() == ib->size()) {
      for (size_t i = 0; i < ia->size(); ++i)
        collect_differences(*f.element, (*ia)[i], (*ib)[i], path + "/" + std::to_string(i) + "/", out);
    } else if (*ia != *ib) {
      out.push_back(path);
    }
  }
}

}  // namespace

json blend_scalar_json(const FieldDesc& field, const json& a, const json& b, double t) {
  if (is_numeric(field.kind)) return lerp_number(field.kind, a, b, t);
  return t < 0.5 ? a : b;  // booleans and enum names switch halfway
}

json blend_field_json(const FieldDesc& field, const json& a, const json& b, double t) {
  if (is_numeric(field.kind)) {
    if (a.is_array() && b.is_array() && a.size() == b.size()) {
      json out = json::array();
      for (size_t i = 0; i < a.size(); ++i) out.push_back(lerp_number(field.kind, a[i], b[i], t));
      return out;
    }
    return lerp_number(field.kind, a, b, t);
  }
  if (field.kind == FieldKind::object && a.is_object() && b.is_object())
    return blend_object_json(*field.element, a, b, t);
  if (field.kind == FieldKind::array && a.is_array() && b.is_array() && a.size() == b.size()) {
    json out = json::array();
    for (size_t i = 0; i < a.size(); ++i) out.push_back(blend_object_json(*field.element, a[i], b[i], t));
    return out;
  }
  return t < 0.5 ? a : b;
}

json blend_object_json(const TypeDesc& type, const json& a, const json& b, double t) {
  json out = json::object();
  for (const FieldDesc& f : type.fields) {
    auto ia = a.find(f.name), ib = b.find(f.name);
    if (ia != a.end() && ib != b.end()) out[f.name] = blend_field_json(f, *ia, *ib, t);
    else if (ia != a.end()) out[f.name] = *ia;
    else if (ib != b.end()) out[f.name] = *ib;
  }
  return out;
}

std::vector<std::string> differing_fields(const TypeDesc& type, const json& a, const json& b) {
  std::vector<std::string> out;
  collect_differences(type, a, b, "", out);
  return out;
}

}  // namespace welkin::editor
