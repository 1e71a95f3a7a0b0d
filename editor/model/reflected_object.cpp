#include "model/reflected_object.h"

#include <new>

#include "welkin/scene/json_fields.h"

namespace welkin::editor {

ReflectedObject::ReflectedObject(const TypeDesc& type) : type_(&type) {
  storage_ = ::operator new(type.size, std::align_val_t(type.align));
  type.ops.construct(storage_);
}

ReflectedObject::ReflectedObject(const TypeDesc& type, const void* source) : ReflectedObject(type) {
  type.ops.copy_assign(storage_, source);
}

ReflectedObject::~ReflectedObject() {
  type_->ops.destroy(storage_);
  ::operator delete(storage_, std::align_val_t(type_->align));
}

nlohmann::json ReflectedObject::to_json() const { return object_to_json(*type_, storage_); }

void ReflectedObject::read(const nlohmann::json& fields) { object_from_json(*type_, storage_, fields); }

nlohmann::json default_component_json(const TypeDesc& type) { return ReflectedObject(type).to_json(); }

nlohmann::json complete_component_json(const TypeDesc& type, const nlohmann::json& fields) {
  ReflectedObject object(type);
  object.read(fields);
  return object.to_json();
}

nlohmann::ordered_json in_declaration_order(const TypeDesc& type, const nlohmann::json& value) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const FieldDesc& f : type.fields) {
    auto it = value.find(f.name);
    if (it == value.end()) continue;
    if (f.kind == FieldKind::object && it->is_object()) {
      out[f.name] = in_declaration_order(*f.element, *it);
    } else if (f.kind == FieldKind::array && it->is_array()) {
      nlohmann::ordered_json elements = nlohmann::ordered_json::array();
      for (const auto& e : *it) elements.push_back(in_declaration_order(*f.element, e));
      out[f.name] = std::move(elements);
    } else {
      out[f.name] = nlohmann::ordered_json::parse(it->dump());
    }
  }
  return out;
}

}  // namespace welkin::editor
