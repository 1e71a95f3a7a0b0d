#pragma once
// Reflection: one declaration per component type gives its fields (name, kind, unit, range,
// default, tooltip, enum names, nested arrays of structs). JSON load/save, validation, field paths
// for sequences and `--set`, and the editor inspector all read this and nothing else.
//
//   struct Fog { static constexpr std::string_view kTypeName = "demo.Fog"; float density = 0.1f; };
//   inline void describe(welkin::TypeBuilder<Fog>& t) {
//     t.field("density", &Fog::density).unit("1/km").range(0, 10).tooltip("Extinction at sea level");
//   }
#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "welkin/core/type_id.h"

namespace welkin {

enum class FieldKind {
  boolean,
  integer,
  f32,
  f64,
  vec2,
  vec3,
  vec4,
  dvec3,
  color,
  enumeration,
  string,
  array,
  object
};
const char* field_kind_name(FieldKind kind);
// Number of scalar components for vector-like kinds (1 for scalars).
int field_kind_arity(FieldKind kind);

struct TypeDesc;

struct EnumValue {
  std::string name;
  int value = 0;
};

// Type-erased access to a std::vector<Element> field.
struct ArrayOps {
  size_t (*size)(const void* vec) = nullptr;
  void (*resize)(void* vec, size_t n) = nullptr;
  void* (*at)(void* vec, size_t i) = nullptr;
};

struct FieldDesc {
  std::string name;
  FieldKind kind = FieldKind::f32;
  size_t offset = 0;
  std::string unit;
  std::optional<double> min, max;  // inclusive, applied to every scalar component
  std::string tooltip;
  std::vector<EnumValue> enum_values;
  const TypeDesc* element = nullptr;  // for arrays of structs and nested structs
  ArrayOps array;
  size_t max_count = 64;  // arrays are bounded: untrusted files cannot ask for a billion layers

  void* ptr(void* object) const { return static_cast<std::byte*>(object) + offset; }
  const void* ptr(const void* object) const { return static_cast<const std::byte*>(object) + offset; }
  const EnumValue* enum_by_name(std::string_view n) const;
  const EnumValue* enum_by_value(int v) const;
};

// Lifetime operations of a reflected type, so pools and arrays can hold it without knowing it.
struct TypeOps {
  void (*construct)(void* at) = nullptr;
  void (*destroy)(void* at) = nullptr;
  void (*move_construct)(void* at, void* from) = nullptr;
  void (*move_assign)(void* to, void* from) = nullptr;
  void (*copy_assign)(void* to, const void* from) = nullptr;
};

struct TypeDesc {
  std::string name;
  TypeId id = 0;
  size_t size = 0, align = 0;
  std::string tooltip;
  std::vector<FieldDesc> fields;
  TypeOps ops;
  std::shared_ptr<void> defaults;  // a default-constructed instance: the declared defaults
  // Cross-field checks (e.g. top radius above bottom radius); throws Error with a field path.
  void (*validate)(const void* object) = nullptr;

  const FieldDesc* field(std::string_view n) const;
};

template <class T> TypeOps make_type_ops() {
  return TypeOps{
      .construct = [](void* at) { new (at) T(); },
      .destroy = [](void* at) { static_cast<T*>(at)->~T(); },
      .move_construct = [](void* at, void* from) { new (at) T(std::move(*static_cast<T*>(from))); },
      .move_assign = [](void* to, void* from) { *static_cast<T*>(to) = std::move(*static_cast<T*>(from)); },
      .copy_assign = [](void* to, const void* from) { *static_cast<T*>(to) = *static_cast<const T*>(from); },
  };
}

template <class T> class TypeBuilder;
template <class T> const TypeDesc& type_desc();

namespace detail {
template <class F> struct IsVector : std::false_type {};
template <class E> struct IsVector<std::vector<E>> : std::true_type { using element = E; };

template <class F> constexpr FieldKind kind_of() {
  if constexpr (std::is_same_v<F, bool>) return FieldKind::boolean;
  else if constexpr (std::is_enum_v<F>) return FieldKind::enumeration;
  else if constexpr (std::is_same_v<F, int>) return FieldKind::integer;
  else if constexpr (std::is_same_v<F, float>) return FieldKind::f32;
  else if constexpr (std::is_same_v<F, double>) return FieldKind::f64;
  else if constexpr (std::is_same_v<F, glm::vec2>) return FieldKind::vec2;
  else if constexpr (std::is_same_v<F, glm::vec3>) return FieldKind::vec3;
  else if constexpr (std::is_same_v<F, glm::vec4>) return FieldKind::vec4;
  else if constexpr (std::is_same_v<F, glm::dvec3>) return FieldKind::dvec3;
  else if constexpr (std::is_same_v<F, std::string>) return FieldKind::string;
  else if constexpr (IsVector<F>::value) return FieldKind::array;
  else if constexpr (std::is_class_v<F>) return FieldKind::object;
  else static_assert(sizeof(F) == 0, "unsupported reflected field type");
}
}  // namespace detail

// Fluent setter for the field just added.
class FieldBuilder {
 public:
  explicit FieldBuilder(FieldDesc& f) : f_(f) {}
  FieldBuilder& unit(std::string u) { f_.unit = std::move(u); return *this; }
  FieldBuilder& range(double lo, double hi) { f_.min = lo; f_.max = hi; return *this; }
  FieldBuilder& min(double lo) { f_.min = lo; return *this; }
  FieldBuilder& max(double hi) { f_.max = hi; return *this; }
  FieldBuilder& tooltip(std::string t) { f_.tooltip = std::move(t); return *this; }
  // A vec3 that is a linear RGB colour (the editor shows a colour picker).
  FieldBuilder& color() { f_.kind = FieldKind::color; return *this; }
  FieldBuilder& values(std::vector<EnumValue> v) { f_.enum_values = std::move(v); return *this; }
  FieldBuilder& max_count(size_t n) { f_.max_count = n; return *this; }

 private:
  FieldDesc& f_;
};

template <class T> class TypeBuilder {
 public:
  explicit TypeBuilder(TypeDesc& d) : d_(d) {}
  void tooltip(std::string t) { d_.tooltip = std::move(t); }
  // A check run after every load or edit of the whole object; throw welkin::Error naming the field.
  void validate(void (*fn)(const T&)) {
    validate_fn_slot() = fn;
    d_.validate = [](const void* o) { validate_fn_slot()(*static_cast<const T*>(o)); };
  }

  template <class F> FieldBuilder field(std::string name, F T::*member) {
    const T& probe = *static_cast<const T*>(d_.defaults.get());
    FieldDesc f;
    f.name = std::move(name);
    f.kind = detail::kind_of<F>();
    f.offset = size_t(reinterpret_cast<const std::byte*>(&(probe.*member)) -
                      reinterpret_cast<const std::byte*>(&probe));
    if constexpr (detail::IsVector<F>::value) {
      using E = typename detail::IsVector<F>::element;
      f.element = &type_desc<E>();
      f.array = ArrayOps{
          .size = [](const void* v) { return static_cast<const F*>(v)->size(); },
          .resize = [](void* v, size_t n) { static_cast<F*>(v)->resize(n); },
          .at = [](void* v, size_t i) -> void* { return &(*static_cast<F*>(v))[i]; },
      };
    } else if constexpr (detail::kind_of<F>() == FieldKind::object) {
      f.element = &type_desc<F>();
    }
    d_.fields.push_back(std::move(f));
    return FieldBuilder(d_.fields.back());
  }

 private:
  static void (*&validate_fn_slot())(const T&) {
    static void (*fn)(const T&) = nullptr;
    return fn;
  }
  TypeDesc& d_;
};

// The description of T, built once from `describe(TypeBuilder<T>&)` (found by argument lookup).
template <class T> const TypeDesc& type_desc() {
  static const TypeDesc desc = [] {
    TypeDesc d;
    d.name = std::string(T::kTypeName);
    d.id = type_id_of_name(T::kTypeName);
    d.size = sizeof(T);
    d.align = alignof(T);
    d.ops = make_type_ops<T>();
    d.defaults = std::make_shared<T>();
    TypeBuilder<T> b(d);
    describe(b);
    return d;
  }();
  return desc;
}

}  // namespace welkin
