#pragma once
// Field paths address one reflected value inside a component: "layers/0/coverage" or
// "rayleigh_scattering/2". Sequences, presets, `--set` and the editor all go through here.
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin {

struct FieldRef {
  const FieldDesc* field = nullptr;  // the field reached
  void* value = nullptr;             // points at the field's storage
  int component = -1;                // >= 0 when the path selected one element of a vector
  std::string path;                  // the path as resolved (for messages)
  const TypeDesc* root_type = nullptr;  // the component, whose cross-field checks run after an edit
  void* root = nullptr;

  bool is_scalar() const;  // bool, integer, float, double, enum or one vector element
  double get_scalar() const;
  // Range-checked, then the component's cross-field checks; a rejected edit changes nothing.
  // Throws Error naming the path.
  void set_scalar(double v) const;
  void set_json(const nlohmann::json& j) const;
  nlohmann::json get_json() const;
};

// Resolves `path` inside `object` of `type`; throws Error naming the first bad segment.
FieldRef resolve_field(const TypeDesc& type, void* object, std::string_view path);

class World;
// Sets `path` of `component` (its registered name, e.g. "timeofday.TimeOfDay") on the first entity
// that has it, loading its module and giving it to a new entity when none has; throws Error naming
// the component and the path. What `--set` and a host program's Sky::set do.
void set_scene_field(World& world, std::string_view component, std::string_view path,
                     const nlohmann::json& value);
// The value at `path` of the first entity that has `component`; throws Error when none has it.
nlohmann::json get_scene_field(World& world, std::string_view component, std::string_view path);

}  // namespace welkin
