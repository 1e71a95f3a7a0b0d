#include "welkin/core/reflection.h"

namespace welkin {

const char* field_kind_name(FieldKind k) {
  switch (k) {
    case FieldKind::boolean: return "boolean";
    case FieldKind::integer: return "integer";
    case FieldKind::f32:
    case FieldKind::f64: return "number";
    case FieldKind::vec2: return "array of 2 numbers";
    case FieldKind::vec3: return "array of 3 numbers";
    case FieldKind::vec4: return "array of 4 numbers";
    case FieldKind::dvec3: return "array of 3 numbers";
    case FieldKind::color: return "RGB colour (array of 3 numbers)";
    case FieldKind::enumeration: return "enumeration name (string)";
    case FieldKind::string: return "string";
    case FieldKind::array: return "array of objects";
    case FieldKind::object: return "object";
  }
  return "?";
}

int field_kind_arity(FieldKind k) {
  switch (k) {
    case FieldKind::vec2: return 2;
    case FieldKind::vec3:
    case FieldKind::dvec3:
    case FieldKind::color: return 3;
    case FieldKind::vec4: return 4;
    default: return 1;
  }
}

const EnumValue* FieldDesc::enum_by_name(std::string_view n) const {
  for (const auto& e : enum_values)
    if (e.name == n) return &e;
  return nullptr;
}

const EnumValue* FieldDesc::enum_by_value(int v) const {
  for (const auto& e : enum_values)
    if (e.value == v) return &e;
  return nullptr;
}

const FieldDesc* TypeDesc::field(std::string_view n) const {
  for (const auto& f : fields)
    if (f.name == n) return &f;
  return nullptr;
}

}  // namespace welkin
