#pragma once
// Blending and comparing reflected values as JSON, driven by the type description: presets blend
// with it, the timeline interpolates keyframes with it, the preset browser diffs with it.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "welkin/core/reflection.h"

namespace welkin::editor {

// Linear blend of two values of one field at t in [0, 1]. Numbers (also inside vectors, colours
// and arrays of structs of equal length) use std::lerp, so t = 0 and t = 1 give a and b exactly;
// integers round to nearest. Booleans, enums, strings and arrays of different lengths switch from
// a to b at t = 0.5.
nlohmann::json blend_field_json(const FieldDesc& field, const nlohmann::json& a, const nlohmann::json& b, double t);
// The same for every field of an object of `type`.
nlohmann::json blend_object_json(const TypeDesc& type, const nlohmann::json& a, const nlohmann::json& b, double t);
// One scalar (a field that is a number, or one element of a vector field: `component` >= 0).
nlohmann::json blend_scalar_json(const FieldDesc& field, const nlohmann::json& a, const nlohmann::json& b, double t);

// Paths of the fields whose values differ between two complete values of `type`, in declaration
// order: "mie_g", "rayleigh_density/0/exp_term" (arrays of equal length compare element by element;
// a vector or colour is one field).
std::vector<std::string> differing_fields(const TypeDesc& type, const nlohmann::json& a, const nlohmann::json& b);

}  // namespace welkin::editor
