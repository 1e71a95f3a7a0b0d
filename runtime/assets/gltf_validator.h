#pragma once
// The glTF JSON's validator (gltf_validate.cpp, gltf_validate_meshes.cpp): the checks' helpers, each
// naming the JSON path of the culprit, and one method per top-level array.
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "internal.h"

namespace welkin::assets::detail {

using nlohmann::json;

inline const std::set<std::string> kSupportedRequired = {"KHR_draco_mesh_compression",
                                                         "KHR_mesh_quantization", "KHR_texture_transform",
                                                         "KHR_materials_emissive_strength"};

inline int type_components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// Bytes of one element including the column padding glTF requires for small matrices.
inline uint64_t element_size(const std::string& type, int csize) {
  if (type == "MAT2" && csize == 1) return 8;
  if (type == "MAT3" && csize == 1) return 12;
  if (type == "MAT3" && csize == 2) return 24;
  return uint64_t(type_components(type)) * csize;
}

struct AccessorInfo {
  bool has_view = false;
  int component_type = 0;
  std::string type;
  uint64_t count = 0;
  bool normalized = false;
};

class Validator {
 public:
  Validator(const json& doc, const Container& c, const Source& src)
      : doc_(doc), c_(c), src_(src), lim_(src.options.limits) {}

  void run() {
    if (!doc_.is_object()) fail(src_, "", "a JSON object at the top level", show(doc_));
    asset();
    extensions();
    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images",
                            "materials", "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
      sizes_[key] = array_size(key);
    buffers();
    buffer_views();
    accessors();
    samplers();
    images();
    textures();
    materials();
    meshes();
    nodes();
    scenes();
  }

 private:
  [[noreturn]] void bad(const std::string& path, const std::string& expected, const json& found) {
    fail(src_, path, expected, show(found));
  }

  size_t array_size(const char* key) {
    auto it = doc_.find(key);
    if (it == doc_.end()) return 0;
    const std::string path = std::string("/") + key;
    if (!it->is_array()) bad(path, "an array", *it);
    if (it->size() > lim_.max_array_elements)
      fail(src_, path, "at most " + std::to_string(lim_.max_array_elements) + " entries",
           std::to_string(it->size()) + " entries");
    for (size_t i = 0; i < it->size(); ++i)
      if (!(*it)[i].is_object()) bad(path + "/" + std::to_string(i), "an object", (*it)[i]);
    return it->size();
  }

  const json* opt(const json& o, const char* key) {
    auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
  }

  uint64_t uint(const json& o, const char* key, const std::string& path, bool required, uint64_t dflt,
                uint64_t min = 0, uint64_t max = UINT64_MAX) {
    const json* v = opt(o, key);
    const std::string p = path + "/" + key;
    const std::string range = min == 0 && max == UINT64_MAX ? "a non-negative integer"
                                                            : "an integer in [" + std::to_string(min) + ", " +
                                                                  std::to_string(max) + "]";
    if (!v) {
      if (required) fail(src_, p, range, "nothing (the property is required)");
      return dflt;
    }
    if (!v->is_number_unsigned()) bad(p, range, *v);  // nlohmann keeps non-negative integers unsigned
    const uint64_t x = v->get<uint64_t>();
    if (x < min || x > max) bad(p, range, *v);
    return x;
  }

  int index(const json& o, const char* key, const std::string& path, const char* array, bool required) {
    const size_t n = sizes_[array];
    const json* v = opt(o, key);
    const std::string p = path + "/" + key;
    const std::string expected =
        n ? "an index into /" + std::string(array) + " (0 to " + std::to_string(n - 1) + ")"
          : "no reference (the file has no " + std::string(array) + ")";
    if (!v) {
      if (required) fail(src_, p, expected, "nothing (the property is required)");
      return -1;
    }
    if (!v->is_number_integer() || v->get<int64_t>() < 0 || uint64_t(v->get<int64_t>()) >= n)
      bad(p, expected, *v);
    return int(v->get<int64_t>());
  }

  int index_value(const json& v, const std::string& p, const char* array) {
    const size_t n = sizes_[array];
    if (!v.is_number_integer() || v.get<int64_t>() < 0 || uint64_t(v.get<int64_t>()) >= n)
      bad(p,
          n ? "an index into /" + std::string(array) + " (0 to " + std::to_string(n - 1) + ")"
            : "no reference (the file has no " + std::string(array) + ")",
          v);
    return int(v.get<int64_t>());
  }

  double number(const json& o, const char* key, const std::string& path, double dflt, double min,
                double max) {
    const json* v = opt(o, key);
    if (!v) return dflt;
    const std::string p = path + "/" + key;
    const std::string expected = "a number in [" + fmt(min) + ", " + fmt(max) + "]";
    if (!v->is_number() || !std::isfinite(v->get<double>()) || v->get<double>() < min ||
        v->get<double>() > max)
      bad(p, expected, *v);
    return v->get<double>();
  }

  static std::string fmt(double x) {
    if (x == HUGE_VAL) return "inf";
    if (x == -HUGE_VAL) return "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
  }

  void number_array(const json& o, const char* key, const std::string& path, size_t n, double min,
                    double max) {
    const json* v = opt(o, key);
    if (!v) return;
    const std::string p = path + "/" + key;
    const std::string expected = std::to_string(n) + " numbers in [" + fmt(min) + ", " + fmt(max) + "]";
    if (!v->is_array() || v->size() != n) bad(p, expected, *v);
    for (size_t i = 0; i < n; ++i) {
      const json& x = (*v)[i];
      if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < min || x.get<double>() > max)
        bad(p + "/" + std::to_string(i), expected, x);
    }
  }

  std::string string(const json& o, const char* key, const std::string& path, bool required) {
    const json* v = opt(o, key);
    const std::string p = path + "/" + key;
    if (!v) {
      if (required) fail(src_, p, "a string", "nothing (the property is required)");
      return {};
    }
    if (!v->is_string()) bad(p, "a string", *v);
    return v->get<std::string>();
  }

  void boolean(const json& o, const char* key, const std::string& path) {
    const json* v = opt(o, key);
    if (v && !v->is_boolean()) bad(path + "/" + key, "true or false", *v);
  }

  const json* object(const json& o, const char* key, const std::string& path) {
    const json* v = opt(o, key);
    if (v && !v->is_object()) bad(path + "/" + key, "an object", *v);
    return v;
  }

  const json& at(const char* array, size_t i) { return doc_[array][i]; }

  // The checks of each top-level array (and of the asset and extensions), in the order run() calls them,
  // and the parts they share.
  void asset();
  void extensions();
  void buffers();
  void buffer_views();
  void accessors();
  void samplers();
  void images();
  void textures();
  void texture_info(const json& m, const char* key, const std::string& path);
  void materials();
  // Component types an attribute may use: core glTF, widened by KHR_mesh_quantization when declared.
  void attribute_format(const std::string& name, int accessor, const std::string& path);
  void meshes();
  void primitive(const json& pr, const std::string& pp, uint64_t& total_vertices, uint64_t& total_indices);
  void nodes();
  void scenes();

  const json& doc_;
  const Container& c_;
  const Source& src_;
  const LoadLimits& lim_;
  std::map<std::string, size_t> sizes_;
  std::set<std::string> used_;
  std::vector<uint64_t> buffer_lengths_, view_lengths_, view_strides_;
  std::vector<AccessorInfo> accessors_;
  std::vector<int> parents_;
};

}  // namespace welkin::assets::detail
