#pragma once
// Reflected values to and from JSON. Reading validates everything (type, arity, range, finiteness,
// enum names, unknown keys) and throws welkin::Error with the JSON path of the bad value.
#include <nlohmann/json_fwd.hpp>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin {

nlohmann::json object_to_json(const TypeDesc& type, const void* object);
nlohmann::json field_to_json(const FieldDesc& field, const void* value);

// Reads `j` into `object`; fields missing from `j` keep their current (default) values.
void object_from_json(const TypeDesc& type, void* object, const nlohmann::json& j);
// Reads one field value (value points at the field itself, not at the owning object).
void field_from_json(const FieldDesc& field, void* value, const nlohmann::json& j);

// Checks an object that never went through JSON (built in code, edited by a system): every value
// finite and in its declared range, arrays within bounds, then the type's cross-field checks.
// Throws Error with the path of the first bad value, relative to the object ("/layers/0/coverage").
void check_object(const TypeDesc& type, const void* object);

// A short description of a JSON value for error messages: `"abc"`, `12.5`, `an object`.
std::string describe_json(const nlohmann::json& j);
// Bounds for every JSON document Welkin reads (scenes, sequences, presets, manifests, editor config),
// checked before parsing: nlohmann's parser and destructor would otherwise recurse or allocate
// without limit on a hostile file.
inline constexpr size_t kMaxJsonBytes = 16u << 20;
inline constexpr int kMaxJsonDepth = 64;

// Parses JSON text, refusing a key repeated in one object (nlohmann keeps the last one, silently):
// throws DuplicateJsonKey with the JSON path of the second key, or nlohmann's own exceptions. Linear
// in the text; the caller bounds its size and depth first.
struct DuplicateJsonKey {
  std::string path;
};
nlohmann::json parse_json_unique_keys(std::string_view text);
// Parses text within the bounds above, refusing duplicate keys (nlohmann would silently keep the
// last), turning syntax errors into an Error with line and column.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);
// Reads a regular file of at most kMaxJsonBytes and parses it (clear errors for missing, unreadable,
// empty, truncated files, FIFOs and devices).
nlohmann::json read_json_file(const std::string& file);

}  // namespace welkin
