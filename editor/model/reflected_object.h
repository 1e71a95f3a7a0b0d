#pragma once
// A heap instance of a reflected type built from its TypeDesc alone. Edits are made on such a copy
// and copied back only when they validate, so a rejected value never leaves a half-written field.
#include <nlohmann/json.hpp>

#include "welkin/core/reflection.h"

namespace welkin::editor {

class ReflectedObject {
 public:
  // The declared defaults of `type`.
  explicit ReflectedObject(const TypeDesc& type);
  // A copy of `source`, an instance of `type`.
  ReflectedObject(const TypeDesc& type, const void* source);
  ~ReflectedObject();
  ReflectedObject(const ReflectedObject&) = delete;
  ReflectedObject& operator=(const ReflectedObject&) = delete;

  const TypeDesc& type() const { return *type_; }
  void* get() { return storage_; }
  const void* get() const { return storage_; }
  nlohmann::json to_json() const;
  // Reads `fields` over the current values; throws Error with the JSON path of a bad value.
  void read(const nlohmann::json& fields);
  void copy_to(void* target) const { type_->ops.copy_assign(target, storage_); }

 private:
  const TypeDesc* type_;
  void* storage_ = nullptr;
};

// The declared defaults of `type` as JSON (every field).
nlohmann::json default_component_json(const TypeDesc& type);
// Every field of `type`: the declared defaults overlaid with `fields` (validated, throws Error).
// Numbers come back in their stored precision, so two completed values compare exactly.
nlohmann::json complete_component_json(const TypeDesc& type, const nlohmann::json& fields);

// `value` (an object of `type`) with its keys in declaration order, nested structs and arrays of
// structs too, so files the editor writes read like the component's declaration.
nlohmann::ordered_json in_declaration_order(const TypeDesc& type, const nlohmann::json& value);

}  // namespace welkin::editor
