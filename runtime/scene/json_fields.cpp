#include "welkin/scene/json_fields.h"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <unordered_set>

#include "welkin/core/error.h"
#include "welkin/core/files.h"

namespace welkin {

using nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& expected, const std::string& found,
                       const std::string& message = {}) {
  throw Error(ErrorInfo{.path = path, .expected = expected, .found = found, .message = message});
}

// Floats are written with their shortest round-trip text (0.1f -> 0.1), so a save/load cycle is
// exact and files stay readable.
json float_json(float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return json(std::strtod(std::string(buf, r.ptr).c_str(), nullptr));
}

double read_number(const json& j, const FieldDesc& f, const std::string& path) {
  if (!j.is_number()) fail(path, "number", describe_json(j));
  double v = j.get<double>();
  if (!std::isfinite(v)) fail(path, "finite number", describe_json(j));
  if ((f.min && v < *f.min) || (f.max && v > *f.max)) {
    std::ostringstream range;
    range << "number in [";
    if (f.min) range << *f.min; else range << "-inf";
    range << ", ";
    if (f.max) range << *f.max; else range << "inf";
    range << "]" << (f.unit.empty() ? "" : " " + f.unit);
    std::ostringstream found;
    found << v;
    fail(path, range.str(), found.str(), "value out of range");
  }
  return v;
}

template <class V> void read_vector(const json& j, const FieldDesc& f, V& out, const std::string& path) {
  int n = field_kind_arity(f.kind);
  if (!j.is_array() || int(j.size()) != n) fail(path, field_kind_name(f.kind), describe_json(j));
  for (int i = 0; i < n; ++i)
    out[i] = typename V::value_type(read_number(j[i], f, path + "/" + std::to_string(i)));
}

void read_field(const FieldDesc& f, void* p, const json& j, const std::string& path) {
  switch (f.kind) {
    case FieldKind::boolean:
      if (!j.is_boolean()) fail(path, "true or false", describe_json(j));
      *static_cast<bool*>(p) = j.get<bool>();
      return;
    case FieldKind::integer: {
      double v = read_number(j, f, path);
      if (!j.is_number_integer() || v < INT32_MIN || v > INT32_MAX) fail(path, "integer", describe_json(j));
      *static_cast<int*>(p) = int(v);
      return;
    }
    case FieldKind::f32: {
      double v = read_number(j, f, path);
      if (std::abs(v) > 3.0e38) fail(path, "number representable as a 32-bit float", describe_json(j));
      *static_cast<float*>(p) = float(v);
      return;
    }
    case FieldKind::f64: *static_cast<double*>(p) = read_number(j, f, path); return;
    case FieldKind::vec2: read_vector(j, f, *static_cast<glm::vec2*>(p), path); return;
    case FieldKind::vec3:
    case FieldKind::color: read_vector(j, f, *static_cast<glm::vec3*>(p), path); return;
    case FieldKind::vec4: read_vector(j, f, *static_cast<glm::vec4*>(p), path); return;
    case FieldKind::dvec3: read_vector(j, f, *static_cast<glm::dvec3*>(p), path); return;
    case FieldKind::enumeration: {
      std::string names;
      for (const auto& e : f.enum_values) names += (names.empty() ? "" : ", ") + ("\"" + e.name + "\"");
      if (!j.is_string()) fail(path, "one of " + names, describe_json(j));
      const EnumValue* e = f.enum_by_name(j.get<std::string>());
      if (!e) fail(path, "one of " + names, describe_json(j));
      *static_cast<int*>(p) = e->value;
      return;
    }
    case FieldKind::string:
      if (!j.is_string()) fail(path, "string", describe_json(j));
      *static_cast<std::string*>(p) = j.get<std::string>();
      return;
    case FieldKind::array: {
      if (!j.is_array()) fail(path, "array of " + f.element->name + " objects", describe_json(j));
      if (j.size() > f.max_count)
        fail(path, "at most " + std::to_string(f.max_count) + " elements",
             std::to_string(j.size()) + " elements");
      // The array is the document's: each element starts from its type's defaults, not from the
      // element the defaults held at its index (a scene's second cloud layer took the default
      // altostratus's wind, shape and shadow wherever it left them unsaid).
      f.array.resize(p, 0);
      f.array.resize(p, j.size());
      for (size_t i = 0; i < j.size(); ++i) {
        std::string ep = path + "/" + std::to_string(i);
        try {
          object_from_json(*f.element, f.array.at(p, i), j[i]);
        } catch (const Error& e) {
          throw e.with_path_prefix(ep);
        }
      }
      return;
    }
    case FieldKind::object:
      try {
        object_from_json(*f.element, p, j);
      } catch (const Error& e) {
        throw e.with_path_prefix(path);
      }
      return;
  }
}

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

void check_fields(const TypeDesc& type, const void* object, const std::string& path) {
  for (const FieldDesc& f : type.fields) {
    const void* p = f.ptr(object);
    std::string fp = path + "/" + f.name;
    auto check = [&](double v, const std::string& at) {
      if (!std::isfinite(v)) fail(at, "finite number", number_text(v));
      if ((f.min && v < *f.min) || (f.max && v > *f.max))
        fail(at,
             "number in [" + number_text(f.min.value_or(-INFINITY)) + ", " +
                 number_text(f.max.value_or(INFINITY)) + "]",
             number_text(v), "value out of range");
    };
    int n = field_kind_arity(f.kind);
    switch (f.kind) {
      case FieldKind::integer: check(*static_cast<const int*>(p), fp); break;
      case FieldKind::f32: check(*static_cast<const float*>(p), fp); break;
      case FieldKind::f64: check(*static_cast<const double*>(p), fp); break;
      case FieldKind::vec2:
      case FieldKind::vec3:
      case FieldKind::vec4:
      case FieldKind::color:
        for (int i = 0; i < n; ++i) check(static_cast<const float*>(p)[i], fp + "/" + std::to_string(i));
        break;
      case FieldKind::dvec3:
        for (int i = 0; i < 3; ++i) check(static_cast<const double*>(p)[i], fp + "/" + std::to_string(i));
        break;
      case FieldKind::enumeration:
        if (!f.enum_by_value(*static_cast<const int*>(p)))
          fail(fp, "a declared enumeration value", std::to_string(*static_cast<const int*>(p)));
        break;
      case FieldKind::array: {
        size_t count = f.array.size(p);
        if (count > f.max_count)
          fail(fp, "at most " + std::to_string(f.max_count) + " elements", std::to_string(count));
        for (size_t i = 0; i < count; ++i)
          check_fields(*f.element, f.array.at(const_cast<void*>(p), i), fp + "/" + std::to_string(i));
        break;
      }
      case FieldKind::object: check_fields(*f.element, p, fp); break;
      default: break;
    }
  }
  if (type.validate) {
    try {
      type.validate(object);
    } catch (const Error& e) {
      throw e.with_path_prefix(path);
    }
  }
}

}  // namespace

void check_object(const TypeDesc& type, const void* object) { check_fields(type, object, ""); }

std::string describe_json(const json& j) {
  switch (j.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array of " + std::to_string(j.size());
    case json::value_t::null: return "null";
    default: {
      std::string s = j.dump();
      return s.size() > 60 ? s.substr(0, 57) + "..." : s;
    }
  }
}

json field_to_json(const FieldDesc& f, const void* p) {
  switch (f.kind) {
    case FieldKind::boolean: return *static_cast<const bool*>(p);
    case FieldKind::integer: return *static_cast<const int*>(p);
    case FieldKind::f32: return float_json(*static_cast<const float*>(p));
    case FieldKind::f64: return *static_cast<const double*>(p);
    case FieldKind::vec2:
    case FieldKind::vec3:
    case FieldKind::color:
    case FieldKind::vec4: {
      json a = json::array();
      for (int i = 0; i < field_kind_arity(f.kind); ++i)
        a.push_back(float_json(static_cast<const float*>(p)[i]));
      return a;
    }
    case FieldKind::dvec3: {
      auto& v = *static_cast<const glm::dvec3*>(p);
      return json::array({v.x, v.y, v.z});
    }
    case FieldKind::enumeration: {
      const EnumValue* e = f.enum_by_value(*static_cast<const int*>(p));
      return e ? json(e->name) : json(*static_cast<const int*>(p));
    }
    case FieldKind::string: return *static_cast<const std::string*>(p);
    case FieldKind::array: {
      json a = json::array();
      void* vec = const_cast<void*>(p);
      for (size_t i = 0; i < f.array.size(p); ++i)
        a.push_back(object_to_json(*f.element, f.array.at(vec, i)));
      return a;
    }
    case FieldKind::object: return object_to_json(*f.element, p);
  }
  return nullptr;
}

json object_to_json(const TypeDesc& type, const void* object) {
  json j = json::object();
  for (const auto& f : type.fields) j[f.name] = field_to_json(f, f.ptr(object));
  return j;
}

void field_from_json(const FieldDesc& f, void* value, const json& j) { read_field(f, value, j, ""); }

void object_from_json(const TypeDesc& type, void* object, const json& j) {
  if (!j.is_object()) fail("", type.name + " object", describe_json(j));
  for (auto it = j.begin(); it != j.end(); ++it) {
    const FieldDesc* f = type.field(it.key());
    if (!f) {
      std::string names;
      for (const auto& fd : type.fields) names += (names.empty() ? "" : ", ") + fd.name;
      fail("/" + it.key(), "a field of " + type.name + " (" + names + ")", "'" + it.key() + "'",
           "unknown field");
    }
    read_field(*f, f->ptr(object), it.value(), "/" + it.key());
  }
  if (type.validate) type.validate(object);
}

namespace {

// Byte offset of the first [ or { nested deeper than `max_depth`, or npos. Linear, no recursion.
size_t too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (ch == '\\') escaped = true;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > max_depth) return i;
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

std::string line_column(const std::string& text, size_t byte) {
  size_t line = 1, col = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') ++line, col = 1;
    else ++col;
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

// Builds the document as nlohmann's own DOM parser does and refuses a repeated key on the way: the
// insert into an object's map says whether the key was there. One pass, linear in the text. (Not a
// parser callback: nlohmann 3.11's callback parser scans the enclosing container at the end of every
// object or array, which is quadratic in the members of one object.)
class UniqueKeyDom {
 public:
  json root;

  bool null() { return place(nullptr); }
  bool boolean(bool v) { return place(v); }
  bool number_integer(json::number_integer_t v) { return place(v); }
  bool number_unsigned(json::number_unsigned_t v) { return place(v); }
  bool number_float(json::number_float_t v, const json::string_t&) { return place(v); }
  bool string(json::string_t& v) { return place(v); }
  bool binary(json::binary_t& v) { return place(json::binary(v)); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    Frame& f = open_.back();
    auto [it, inserted] = f.value->get_ref<json::object_t&>().emplace(k, nullptr);
    if (!inserted) throw DuplicateJsonKey{path() + "/" + k};
    f.key = &it->first;
    member_ = &it->second;  // map nodes stay where they are: safe to hold
    return true;
  }
  // A syntax error: parse_json_unique_keys parses again for nlohmann's own exception and position.
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) { return false; }

 private:
  struct Frame {
    json* value = nullptr;
    const std::string* key = nullptr;  // objects: the member being parsed
  };
  // Puts a value where the document is at: the root, the next element of an array, or the member
  // whose key came last. An array's elements may move as it grows, but none is held open then.
  json* put(json&& v) {
    if (open_.empty()) {
      root = std::move(v);
      return &root;
    }
    json& parent = *open_.back().value;
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    *member_ = std::move(v);
    return member_;
  }
  bool place(json v) {
    put(std::move(v));
    return true;
  }
  bool open(json container) {
    open_.push_back(Frame{.value = put(std::move(container))});
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }
  // Where the innermost open object is: each open container's member or element, from the root.
  std::string path() const {
    std::string p;
    for (size_t i = 0; i + 1 < open_.size(); ++i)
      p += "/" + (open_[i].value->is_object() ? *open_[i].key : std::to_string(open_[i].value->size() - 1));
    return p;
  }
  std::vector<Frame> open_;
  json* member_ = nullptr;
};

}  // namespace

json parse_json_unique_keys(std::string_view text) {
  UniqueKeyDom dom;
  if (json::sax_parse(text, &dom)) return std::move(dom.root);
  return json::parse(text);  // not valid JSON: throws nlohmann's exception, with the position
}

json parse_json_text(const std::string& text, const std::string& file) {
  if (text.size() > kMaxJsonBytes)
    throw Error(ErrorInfo{.file = file,
                          .expected = "JSON of at most " + std::to_string(kMaxJsonBytes) + " bytes",
                          .found = std::to_string(text.size()) + " bytes"});
  if (size_t at = too_deep_at(text, kMaxJsonDepth); at != std::string::npos)
    throw Error(ErrorInfo{.file = file + ":" + line_column(text, at),
                          .expected = "JSON nested at most " + std::to_string(kMaxJsonDepth) + " levels deep",
                          .found = "deeper nesting"});
  try {
    return parse_json_unique_keys(text);
  } catch (const DuplicateJsonKey& d) {
    throw Error(ErrorInfo{.file = file,
                          .path = d.path,
                          .expected = "each key once per object",
                          .found = "a duplicate key",
                          .message = "duplicate key"});
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    if (auto pos = what.find("syntax error"); pos != std::string::npos) what = what.substr(pos);
    bool truncated = e.byte >= text.size();
    throw Error(ErrorInfo{
        .file = file + ":" + line_column(text, e.byte ? e.byte - 1 : 0),
        .message = std::string(truncated ? "truncated or malformed JSON: " : "malformed JSON: ") + what});
  } catch (const json::exception& e) {
    // e.g. a number too large for a double ("1e999"): nlohmann reports no position for these.
    std::string what = e.what();
    if (auto pos = what.find("] "); pos != std::string::npos) what = what.substr(pos + 2);
    throw Error(ErrorInfo{.file = file, .message = "malformed JSON: " + what});
  }
}

json read_json_file(const std::string& file) {
  std::string text = read_file_text(file, kMaxJsonBytes);
  if (text.empty()) throw Error(ErrorInfo{.file = file, .message = "file is empty"});
  return parse_json_text(text, file);
}

}  // namespace welkin
