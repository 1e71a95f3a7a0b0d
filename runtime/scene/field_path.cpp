#include "welkin/scene/field_path.h"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/json_fields.h"

namespace welkin {

using nlohmann::json;

namespace {

bool parse_index(std::string_view s, size_t& out) {
  if (s.empty()) return false;
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

[[noreturn]] void bad_path(const std::string& resolved, std::string_view segment,
                           const std::string& expected) {
  throw Error(ErrorInfo{.path = resolved + "/" + std::string(segment), .expected = expected,
                        .found = "'" + std::string(segment) + "'", .message = "no such field"});
}

std::string field_names(const TypeDesc& t) {
  std::string s;
  for (const auto& f : t.fields) s += (s.empty() ? "" : ", ") + f.name;
  return s;
}

}  // namespace

FieldRef resolve_field(const TypeDesc& type, void* object, std::string_view path) {
  const TypeDesc* t = &type;
  void* obj = object;
  FieldRef ref;
  std::string resolved;
  while (!path.empty()) {
    size_t slash = path.find('/');
    std::string_view seg = path.substr(0, slash);
    path = slash == std::string_view::npos ? std::string_view{} : path.substr(slash + 1);
    if (ref.field == nullptr || ref.field->kind == FieldKind::object) {
      const TypeDesc* owner = ref.field ? ref.field->element : t;
      void* owner_obj = ref.field ? ref.value : obj;
      const FieldDesc* f = owner->field(seg);
      if (!f) bad_path(resolved, seg, "a field of " + owner->name + " (" + field_names(*owner) + ")");
      ref.field = f;
      ref.value = f->ptr(owner_obj);
    } else if (ref.field->kind == FieldKind::array) {
      size_t i = 0;
      size_t n = ref.field->array.size(ref.value);
      if (!parse_index(seg, i) || i >= n)
        bad_path(resolved, seg, "an index below " + std::to_string(n));
      // Step into the element: the next segment names one of its fields.
      const TypeDesc* et = ref.field->element;
      void* eobj = ref.field->array.at(ref.value, i);
      resolved += "/" + std::string(seg);
      if (path.empty())
        throw Error(ErrorInfo{
            .path = resolved,
            .message = "path ends at an array element; name one of its fields (" + field_names(*et) + ")"});
      size_t s2 = path.find('/');
      std::string_view fseg = path.substr(0, s2);
      path = s2 == std::string_view::npos ? std::string_view{} : path.substr(s2 + 1);
      const FieldDesc* f = et->field(fseg);
      if (!f) bad_path(resolved, fseg, "a field of " + et->name + " (" + field_names(*et) + ")");
      ref.field = f;
      ref.value = f->ptr(eobj);
      seg = fseg;
    } else if (field_kind_arity(ref.field->kind) > 1 && ref.component < 0) {
      size_t i = 0;
      if (!parse_index(seg, i) || i >= size_t(field_kind_arity(ref.field->kind)))
        bad_path(resolved, seg,
                 "a component index below " + std::to_string(field_kind_arity(ref.field->kind)));
      ref.component = int(i);
    } else {
      bad_path(resolved, seg, "end of path (" + ref.field->name + " has no parts)");
    }
    resolved += "/" + std::string(seg);
  }
  if (!ref.field) throw Error(ErrorInfo{.path = "/", .expected = "a field path", .found = "an empty path"});
  ref.path = resolved;
  ref.root_type = &type;
  ref.root = object;
  return ref;
}

bool FieldRef::is_scalar() const {
  switch (field->kind) {
    case FieldKind::boolean:
    case FieldKind::integer:
    case FieldKind::f32:
    case FieldKind::f64:
    case FieldKind::enumeration: return true;
    case FieldKind::vec2:
    case FieldKind::vec3:
    case FieldKind::vec4:
    case FieldKind::color:
    case FieldKind::dvec3: return component >= 0;
    default: return false;
  }
}

double FieldRef::get_scalar() const {
  if (!is_scalar())
    throw Error(
        ErrorInfo{.path = path, .expected = "a numeric field", .found = field_kind_name(field->kind)});
  switch (field->kind) {
    case FieldKind::boolean: return *static_cast<bool*>(value) ? 1.0 : 0.0;
    case FieldKind::integer:
    case FieldKind::enumeration: return *static_cast<int*>(value);
    case FieldKind::f32: return *static_cast<float*>(value);
    case FieldKind::f64: return *static_cast<double*>(value);
    case FieldKind::dvec3: return (*static_cast<glm::dvec3*>(value))[component];
    default: return static_cast<float*>(value)[component];
  }
}

void FieldRef::set_scalar(double v) const {
  if (!is_scalar())
    throw Error(
        ErrorInfo{.path = path, .expected = "a numeric field", .found = field_kind_name(field->kind)});
  if (field->kind == FieldKind::enumeration) {
    if (!field->enum_by_value(int(v)))
      throw Error(
          ErrorInfo{.path = path, .expected = "a valid enumeration value", .found = std::to_string(v)});
    *static_cast<int*>(value) = int(v);
    return;
  }
  json j = v;
  if (field->kind == FieldKind::integer) {
    if (v != std::floor(v))
      throw Error(ErrorInfo{.path = path, .expected = "integer", .found = std::to_string(v)});
    j = int64_t(v);
  }
  if (field->kind == FieldKind::boolean) j = v != 0.0;
  if (component >= 0) {
    // Validate the one element through the same reader as whole values (range, finiteness).
    json whole = field_to_json(*field, value);
    whole[component] = j;
    set_json(whole);
  } else {
    set_json(j);
  }
}

void FieldRef::set_json(const json& j) const {
  json old = field_to_json(*field, value);
  try {
    if (component >= 0 && !j.is_array()) {
      json whole = field_to_json(*field, value);
      whole[component] = j;
      field_from_json(*field, value, whole);
    } else {
      field_from_json(*field, value, j);
    }
  } catch (const Error& e) {
    field_from_json(*field, value, old);  // a vector may have been half written
    throw e.with_path_prefix(path);
  }
  if (root_type && root_type->validate) {
    try {
      root_type->validate(root);
    } catch (const Error&) {
      field_from_json(*field, value, old);
      throw;
    }
  }
}

json FieldRef::get_json() const {
  json j = field_to_json(*field, value);
  return component >= 0 ? j[component] : j;
}

void set_scene_field(World& world, std::string_view component, std::string_view path, const json& value) {
  const ComponentInfo& info = world.modules().require_component(component);
  Registry& reg = world.registry();
  Entity target;
  if (const ComponentPool* pool = reg.pool(info.type->id); pool && !pool->empty())
    target = pool->entities()[0];
  if (target.is_null()) {
    target = reg.create();
    reg.emplace(target, *info.type);
  }
  try {
    resolve_field(*info.type, reg.get(target, info.type->id), path).set_json(value);
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(component));
  }
}

json get_scene_field(World& world, std::string_view component, std::string_view path) {
  const ComponentInfo& info = world.modules().require_component(component);
  Registry& reg = world.registry();
  const ComponentPool* pool = reg.pool(info.type->id);
  if (!pool || pool->empty())
    throw Error(ErrorInfo{
        .path = std::string(component), .expected = "an entity with the component", .found = "none"});
  try {
    return resolve_field(*info.type, reg.get(pool->entities()[0], info.type->id), path).get_json();
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(component));
  }
}

}  // namespace welkin
