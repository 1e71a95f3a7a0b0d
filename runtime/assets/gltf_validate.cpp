// Validation of the glTF JSON before tinygltf sees it: tinygltf trusts indices and ranges in places
// (image bufferViews, Draco streams), substitutes defaults for mistyped values and only warns about
// missing files, so everything the loader relies on is checked here, with the JSON path of the culprit.
#include <algorithm>
#include <cmath>
#include <set>

#include "internal.h"

namespace welkin::assets::detail {

namespace {

using nlohmann::json;

const std::set<std::string> kSupportedRequired = {"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                                  "KHR_texture_transform", "KHR_materials_emissive_strength"};

int type_components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// Bytes of one element including the column padding glTF requires for small matrices.
uint64_t element_size(const std::string& type, int csize) {
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

  void asset() {
    const json* a = object(doc_, "asset", "");
    if (!a) fail(src_, "/asset", "an object with \"version\": \"2.0\"", "nothing (the property is required)");
    const std::string v = string(*a, "version", "/asset", true);
    if (v.size() < 2 || v[0] != '2' || v[1] != '.')
      fail(src_, "/asset/version", "glTF version \"2.x\"", "\"" + v + "\"");
    const std::string mv = string(*a, "minVersion", "/asset", false);
    if (!mv.empty() && mv != "2.0") fail(src_, "/asset/minVersion", "\"2.0\"", "\"" + mv + "\"");
  }

  void extensions() {
    for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
      const json* v = opt(doc_, key);
      if (!v) continue;
      const std::string p = std::string("/") + key;
      if (!v->is_array() || v->size() > 1024) bad(p, "an array of extension names", *v);
      for (size_t i = 0; i < v->size(); ++i)
        if (!(*v)[i].is_string()) bad(p + "/" + std::to_string(i), "an extension name", (*v)[i]);
    }
    if (const json* used = opt(doc_, "extensionsUsed"))
      for (const json& e : *used) used_.insert(e.get<std::string>());
    if (const json* req = opt(doc_, "extensionsRequired")) {
      for (size_t i = 0; i < req->size(); ++i) {
        const std::string name = (*req)[i].get<std::string>();
        if (!kSupportedRequired.count(name))
          fail(src_, "/extensionsRequired/" + std::to_string(i),
               "an extension this loader supports (KHR_draco_mesh_compression, KHR_mesh_quantization, "
               "KHR_texture_transform, KHR_materials_emissive_strength)",
               "\"" + name + "\"");
      }
    }
  }

  void buffers() {
    uint64_t total = 0;
    for (size_t i = 0; i < sizes_["buffers"]; ++i) {
      const json& b = at("buffers", i);
      const std::string p = "/buffers/" + std::to_string(i);
      const uint64_t len = uint(b, "byteLength", p, true, 0, 1, lim_.max_file_bytes);
      buffer_lengths_.push_back(len);
      total += len;
      if (total > lim_.max_file_bytes * 4)
        fail(src_, p + "/byteLength",
             "all buffers together at most " + std::to_string(lim_.max_file_bytes * 4) + " bytes",
             std::to_string(total) + " bytes so far");
      const std::string uri = string(b, "uri", p, false);
      if (!opt(b, "uri")) {
        if (!c_.is_glb || i != 0)
          fail(src_, p + "/uri", c_.is_glb ? "a URI (only buffer 0 may use the GLB BIN chunk)" : "a URI",
               "nothing");
        if (!c_.has_bin) fail(src_, p, "a GLB BIN chunk holding this buffer", "a GLB without BIN chunk");
        if (len > c_.bin.size())
          fail(src_, p + "/byteLength", "at most the BIN chunk length " + std::to_string(c_.bin.size()),
               std::to_string(len));
        continue;
      }
      const DataUriKind kind = data_uri_kind(uri);
      if (kind == DataUriKind::buffer || kind == DataUriKind::image) {
        const uint64_t n = data_uri_decoded_size(uri);
        if (n != len)
          fail(src_, p + "/uri", "base64 data of byteLength " + std::to_string(len) + " bytes",
               std::to_string(n) + " bytes");
      } else if (kind == DataUriKind::unsupported) {
        fail(src_, p + "/uri", "a base64 data URI (application/octet-stream or application/gltf-buffer)",
             "\"" + uri.substr(0, std::min<size_t>(uri.size(), 40)) + "\"");
      } else {
        const auto file = resolve_external(src_, uri, p + "/uri");
        std::error_code ec;
        const uint64_t size = std::filesystem::file_size(file, ec);
        if (ec || size != len)
          fail(src_, p + "/byteLength", "the size of \"" + uri + "\" (" + std::to_string(size) + " bytes)",
               std::to_string(len));
      }
    }
  }

  void buffer_views() {
    for (size_t i = 0; i < sizes_["bufferViews"]; ++i) {
      const json& v = at("bufferViews", i);
      const std::string p = "/bufferViews/" + std::to_string(i);
      const int buffer = index(v, "buffer", p, "buffers", true);
      const uint64_t offset = uint(v, "byteOffset", p, false, 0, 0, lim_.max_file_bytes);
      const uint64_t length = uint(v, "byteLength", p, true, 0, 1, lim_.max_file_bytes);
      const uint64_t stride = uint(v, "byteStride", p, false, 0, 4, 252);
      if (stride % 4 != 0) bad(p + "/byteStride", "a multiple of 4 in [4, 252]", v["byteStride"]);
      if (offset + length > buffer_lengths_[buffer])
        fail(src_, p + "/byteLength",
             "byteOffset + byteLength within buffer " + std::to_string(buffer) + " (" +
                 std::to_string(buffer_lengths_[buffer]) + " bytes)",
             std::to_string(offset) + " + " + std::to_string(length));
      view_lengths_.push_back(length);
      view_strides_.push_back(stride);
    }
  }

  void accessors() {
    const uint64_t max_count = std::max(lim_.max_vertices_per_primitive, lim_.max_indices_per_primitive);
    for (size_t i = 0; i < sizes_["accessors"]; ++i) {
      const json& a = at("accessors", i);
      const std::string p = "/accessors/" + std::to_string(i);
      AccessorInfo info;
      const int view = index(a, "bufferView", p, "bufferViews", false);
      const uint64_t offset = uint(a, "byteOffset", p, false, 0, 0, lim_.max_file_bytes);
      const json* ct = opt(a, "componentType");
      if (!ct) fail(src_, p + "/componentType", "a component type", "nothing (the property is required)");
      const int64_t ctv = ct->is_number_integer() ? ct->get<int64_t>() : 0;
      if (ctv < 5120 || ctv > 5126 || component_size(int(ctv)) == 0)
        bad(p + "/componentType", "5120, 5121, 5122, 5123, 5125 or 5126", *ct);
      info.component_type = int(ct->get<int64_t>());
      info.type = string(a, "type", p, true);
      if (type_components(info.type) == 0)
        fail(src_, p + "/type", "SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4", "\"" + info.type + "\"");
      info.count = uint(a, "count", p, true, 0, 1, max_count);
      boolean(a, "normalized", p);
      info.normalized = a.value("normalized", false);
      if (info.normalized && (info.component_type == 5125 || info.component_type == 5126))
        fail(src_, p + "/normalized", "false for FLOAT and UNSIGNED_INT components", "true");
      if (opt(a, "sparse"))
        fail(src_, p + "/sparse", "no sparse storage (not supported by this loader)", "sparse");
      if (view < 0) {
        if (opt(a, "byteOffset"))
          fail(src_, p + "/byteOffset", "no byteOffset without a bufferView", show(a["byteOffset"]));
      } else {
        info.has_view = true;
        const int csize = component_size(info.component_type);
        const uint64_t esize = element_size(info.type, csize);
        const uint64_t stride = view_strides_[view] ? view_strides_[view] : esize;
        if (stride < esize)
          fail(src_, "/bufferViews/" + std::to_string(view) + "/byteStride",
               "at least the element size " + std::to_string(esize) + " of accessor " + std::to_string(i),
               std::to_string(stride));
        const uint64_t end = offset + stride * (info.count - 1) + esize;
        if (end > view_lengths_[view])
          fail(src_, p,
               "count " + std::to_string(info.count) + " x stride " + std::to_string(stride) +
                   " from byteOffset " + std::to_string(offset) + " within bufferView " +
                   std::to_string(view) + " (" + std::to_string(view_lengths_[view]) + " bytes)",
               "a range ending at byte " + std::to_string(end));
      }
      accessors_.push_back(info);
    }
  }

  void samplers() {
    for (size_t i = 0; i < sizes_["samplers"]; ++i) {
      const json& s = at("samplers", i);
      const std::string p = "/samplers/" + std::to_string(i);
      const auto check = [&](const char* key, std::initializer_list<uint64_t> allowed) {
        if (!opt(s, key)) return;
        const uint64_t v = uint(s, key, p, false, 0);
        if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
          bad(p + "/" + key, "a GL filter or wrap enum glTF allows", s[key]);
      };
      check("magFilter", {9728, 9729});
      check("minFilter", {9728, 9729, 9984, 9985, 9986, 9987});
      check("wrapS", {33071, 33648, 10497});
      check("wrapT", {33071, 33648, 10497});
    }
  }

  void images() {
    for (size_t i = 0; i < sizes_["images"]; ++i) {
      const json& im = at("images", i);
      const std::string p = "/images/" + std::to_string(i);
      const bool has_uri = opt(im, "uri"), has_view = opt(im, "bufferView");
      if (has_uri == has_view)
        fail(src_, p, "exactly one of \"uri\" and \"bufferView\"", has_uri ? "both" : "neither");
      string(im, "mimeType", p, false);
      if (has_view) {
        index(im, "bufferView", p, "bufferViews", true);
        continue;
      }
      const std::string uri = string(im, "uri", p, true);
      const DataUriKind kind = data_uri_kind(uri);
      if (kind == DataUriKind::image || kind == DataUriKind::buffer) {
        if (data_uri_decoded_size(uri) == 0) fail(src_, p + "/uri", "base64 image data", "an empty payload");
      } else if (kind == DataUriKind::unsupported) {
        fail(src_, p + "/uri", "a base64 data URI of image/png or image/jpeg",
             "\"" + uri.substr(0, std::min<size_t>(uri.size(), 40)) + "\"");
      } else {
        const auto file = resolve_external(src_, uri, p + "/uri");
        std::error_code ec;
        const uint64_t size = std::filesystem::file_size(file, ec);
        if (ec || size == 0 || size > lim_.max_file_bytes)
          fail(src_, p + "/uri", "an image file of 1 to " + std::to_string(lim_.max_file_bytes) + " bytes",
               "\"" + uri + "\" of " + std::to_string(size) + " bytes");
      }
    }
  }

  void textures() {
    for (size_t i = 0; i < sizes_["textures"]; ++i) {
      const json& t = at("textures", i);
      const std::string p = "/textures/" + std::to_string(i);
      index(t, "source", p, "images", false);
      index(t, "sampler", p, "samplers", false);
    }
  }

  void texture_info(const json& m, const char* key, const std::string& path) {
    const json* t = object(m, key, path);
    if (!t) return;
    const std::string p = path + "/" + key;
    index(*t, "index", p, "textures", true);
    uint(*t, "texCoord", p, false, 0, 0, 7);
    number(*t, "scale", p, 1.0, -HUGE_VAL, HUGE_VAL);
    number(*t, "strength", p, 1.0, 0.0, 1.0);
    const json* ext = object(*t, "extensions", p);
    if (!ext) return;
    const json* tt = object(*ext, "KHR_texture_transform", p + "/extensions");
    if (!tt) return;
    const std::string tp = p + "/extensions/KHR_texture_transform";
    number_array(*tt, "offset", tp, 2, -HUGE_VAL, HUGE_VAL);
    number(*tt, "rotation", tp, 0.0, -HUGE_VAL, HUGE_VAL);
    number_array(*tt, "scale", tp, 2, -HUGE_VAL, HUGE_VAL);
    uint(*tt, "texCoord", tp, false, 0, 0, 7);
  }

  void materials() {
    for (size_t i = 0; i < sizes_["materials"]; ++i) {
      const json& m = at("materials", i);
      const std::string p = "/materials/" + std::to_string(i);
      string(m, "name", p, false);
      if (const json* pbr = object(m, "pbrMetallicRoughness", p)) {
        const std::string pp = p + "/pbrMetallicRoughness";
        number_array(*pbr, "baseColorFactor", pp, 4, 0.0, 1.0);
        number(*pbr, "metallicFactor", pp, 1.0, 0.0, 1.0);
        number(*pbr, "roughnessFactor", pp, 1.0, 0.0, 1.0);
        texture_info(*pbr, "baseColorTexture", pp);
        texture_info(*pbr, "metallicRoughnessTexture", pp);
      }
      texture_info(m, "normalTexture", p);
      texture_info(m, "occlusionTexture", p);
      texture_info(m, "emissiveTexture", p);
      number_array(m, "emissiveFactor", p, 3, 0.0, 1.0);
      if (const json* e = object(m, "extensions", p))
        if (const json* es = object(*e, "KHR_materials_emissive_strength", p + "/extensions"))
          number(*es, "emissiveStrength", p + "/extensions/KHR_materials_emissive_strength", 1.0, 0.0,
                 HUGE_VAL);
      const std::string mode = string(m, "alphaMode", p, false);
      if (!mode.empty() && mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
        fail(src_, p + "/alphaMode", "\"OPAQUE\", \"MASK\" or \"BLEND\"", "\"" + mode + "\"");
      number(m, "alphaCutoff", p, 0.5, 0.0, HUGE_VAL);
      boolean(m, "doubleSided", p);
    }
  }

  // Component types an attribute may use: core glTF, widened by KHR_mesh_quantization when declared.
  void attribute_format(const std::string& name, int accessor, const std::string& path) {
    const AccessorInfo& a = accessors_[accessor];
    const bool quant = used_.count("KHR_mesh_quantization") > 0;
    const int ct = a.component_type;
    const bool n = a.normalized;
    auto need = [&](const char* type, bool ok, const char* formats) {
      if (a.type != type)
        fail(src_, path, std::string(type) + " accessor",
             "accessor " + std::to_string(accessor) + " of " + a.type);
      if (!ok)
        fail(src_, path, std::string(formats) + (quant ? "" : " (others need KHR_mesh_quantization)"),
             "accessor " + std::to_string(accessor) + " with componentType " + std::to_string(ct) +
                 (n ? " normalized" : ""));
    };
    if (name == "POSITION") {
      need("VEC3", ct == 5126 || (quant && ct != 5125),
           quant ? "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT" : "FLOAT");
    } else if (name == "NORMAL") {
      need("VEC3", ct == 5126 || (quant && (ct == 5120 || ct == 5122) && n),
           quant ? "FLOAT or normalized BYTE/SHORT" : "FLOAT");
    } else if (name == "TANGENT") {
      need("VEC4", ct == 5126 || (quant && (ct == 5120 || ct == 5122) && n),
           quant ? "FLOAT or normalized BYTE/SHORT" : "FLOAT");
    } else if (name == "TEXCOORD_0") {
      const bool core = ct == 5126 || ((ct == 5121 || ct == 5123) && n);
      need("VEC2", core || (quant && ct != 5125),
           quant ? "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
                 : "FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT");
    }
  }

  void meshes() {
    uint64_t total_vertices = 0, total_indices = 0;
    for (size_t i = 0; i < sizes_["meshes"]; ++i) {
      const json& m = at("meshes", i);
      const std::string p = "/meshes/" + std::to_string(i);
      const json* prims = opt(m, "primitives");
      if (!prims || !prims->is_array() || prims->empty() || prims->size() > lim_.max_primitives_per_mesh)
        fail(src_, p + "/primitives",
             "an array of 1 to " + std::to_string(lim_.max_primitives_per_mesh) + " primitives",
             prims ? show(*prims) : "nothing");
      for (size_t j = 0; j < prims->size(); ++j) {
        const json& pr = (*prims)[j];
        const std::string pp = p + "/primitives/" + std::to_string(j);
        if (!pr.is_object()) bad(pp, "an object", pr);
        primitive(pr, pp, total_vertices, total_indices);
      }
    }
  }

  void primitive(const json& pr, const std::string& pp, uint64_t& total_vertices, uint64_t& total_indices) {
    const json* attrs = object(pr, "attributes", pp);
    if (!attrs || attrs->empty())
      fail(src_, pp + "/attributes", "an object of attribute accessors", "nothing");
    const uint64_t mode = uint(pr, "mode", pp, false, 4, 0, 6);
    index(pr, "material", pp, "materials", false);
    const int indices = index(pr, "indices", pp, "accessors", false);
    const json* ext = object(pr, "extensions", pp);
    const json* draco = ext ? object(*ext, "KHR_draco_mesh_compression", pp + "/extensions") : nullptr;
    const std::string dp = pp + "/extensions/KHR_draco_mesh_compression";
    if (draco) {
      if (!used_.count("KHR_draco_mesh_compression"))
        fail(src_, dp, "KHR_draco_mesh_compression listed in /extensionsUsed", "it missing there");
      if (mode != 4)
        fail(src_, pp + "/mode", "4 (TRIANGLES) for a Draco-compressed primitive", std::to_string(mode));
      index(*draco, "bufferView", dp, "bufferViews", true);
      const json* da = object(*draco, "attributes", dp);
      if (!da) fail(src_, dp + "/attributes", "an object of Draco attribute ids", "nothing");
      for (auto it = da->begin(); it != da->end(); ++it) {
        const std::string ap = dp + "/attributes/" + pointer_key(it.key());
        if (!it->is_number_integer() || it->get<int64_t>() < 0 || it->get<int64_t>() > 1 << 20)
          bad(ap, "a Draco attribute unique id", *it);
        if (!attrs->contains(it.key()))
          fail(src_, ap, "an attribute also listed in the primitive's attributes",
               "\"" + it.key() + "\" only here");
      }
    }
    uint64_t count = 0;
    std::string first;
    for (auto it = attrs->begin(); it != attrs->end(); ++it) {
      const std::string ap = pp + "/attributes/" + pointer_key(it.key());
      const int a = index_value(*it, ap, "accessors");
      const bool in_draco = draco && (*draco)["attributes"].contains(it.key());
      if (!accessors_[a].has_view && !in_draco)
        fail(src_, ap, "an accessor with a bufferView (or a Draco-compressed attribute)",
             "accessor " + std::to_string(a) + " without bufferView");
      attribute_format(it.key(), a, ap);
      if (first.empty()) {
        first = it.key();
        count = accessors_[a].count;
      } else if (accessors_[a].count != count) {
        fail(src_, ap, "count " + std::to_string(count) + " like attribute " + first,
             "accessor " + std::to_string(a) + " with count " + std::to_string(accessors_[a].count));
      }
    }
    if (count > lim_.max_vertices_per_primitive)
      fail(src_, pp + "/attributes",
           "at most " + std::to_string(lim_.max_vertices_per_primitive) + " vertices", std::to_string(count));
    total_vertices += count;
    if (total_vertices > lim_.max_total_vertices)
      fail(src_, pp + "/attributes",
           "at most " + std::to_string(lim_.max_total_vertices) + " vertices in all meshes",
           std::to_string(total_vertices) + " so far");
    if (indices >= 0) {
      const AccessorInfo& a = accessors_[indices];
      if (a.type != "SCALAR" ||
          (a.component_type != 5121 && a.component_type != 5123 && a.component_type != 5125) || a.normalized)
        fail(src_, pp + "/indices", "a SCALAR accessor of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
             "accessor " + std::to_string(indices) + " of " + a.type + " componentType " +
                 std::to_string(a.component_type));
      if (!a.has_view && !draco)
        fail(src_, pp + "/indices", "an accessor with a bufferView", "accessor " + std::to_string(indices));
      if (a.count > lim_.max_indices_per_primitive)
        fail(src_, pp + "/indices", "at most " + std::to_string(lim_.max_indices_per_primitive) + " indices",
             std::to_string(a.count));
      total_indices += a.count;
      if (total_indices > lim_.max_total_indices)
        fail(src_, pp + "/indices",
             "at most " + std::to_string(lim_.max_total_indices) + " indices in all meshes",
             std::to_string(total_indices) + " so far");
    } else {
      total_indices += count;
    }
    if (const json* targets = opt(pr, "targets")) {
      if (!targets->is_array() || targets->size() > 256)
        bad(pp + "/targets", "an array of morph targets", *targets);
      for (size_t t = 0; t < targets->size(); ++t) {
        const json& tg = (*targets)[t];
        const std::string tp = pp + "/targets/" + std::to_string(t);
        if (!tg.is_object()) bad(tp, "an object of accessors", tg);
        for (auto it = tg.begin(); it != tg.end(); ++it)
          index_value(*it, tp + "/" + pointer_key(it.key()), "accessors");
      }
    }
  }

  void nodes() {
    const size_t n = sizes_["nodes"];
    parents_.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
      const json& nd = at("nodes", i);
      const std::string p = "/nodes/" + std::to_string(i);
      index(nd, "mesh", p, "meshes", false);
      index(nd, "camera", p, "cameras", false);
      index(nd, "skin", p, "skins", false);
      number_array(nd, "matrix", p, 16, -HUGE_VAL, HUGE_VAL);
      number_array(nd, "translation", p, 3, -HUGE_VAL, HUGE_VAL);
      number_array(nd, "rotation", p, 4, -1.0, 1.0);
      number_array(nd, "scale", p, 3, -HUGE_VAL, HUGE_VAL);
      if (opt(nd, "matrix") && (opt(nd, "translation") || opt(nd, "rotation") || opt(nd, "scale")))
        fail(src_, p + "/matrix", "either matrix or translation/rotation/scale", "both");
      const json* ch = opt(nd, "children");
      if (!ch) continue;
      if (!ch->is_array()) bad(p + "/children", "an array of node indices", *ch);
      for (size_t k = 0; k < ch->size(); ++k) {
        const std::string cp = p + "/children/" + std::to_string(k);
        const int c = index_value((*ch)[k], cp, "nodes");
        if (size_t(c) == i) fail(src_, cp, "another node", "the node itself");
        if (parents_[c] >= 0)
          fail(src_, cp, "a node with one parent",
               "node " + std::to_string(c) + ", already a child of node " + std::to_string(parents_[c]));
        parents_[c] = int(i);
      }
    }
    // With one parent each, a node is in a cycle exactly when walking up never reaches a root.
    std::vector<int> state(n, 0);  // 0 unknown, 1 reaches a root, 2 on the current walk
    for (size_t i = 0; i < n; ++i) {
      std::vector<size_t> walk;
      size_t k = i;
      while (state[k] == 0) {
        state[k] = 2;
        walk.push_back(k);
        if (parents_[k] < 0) break;
        k = size_t(parents_[k]);
      }
      if (state[k] == 2 && parents_[k] >= 0)
        fail(src_, "/nodes/" + std::to_string(k) + "/children", "a tree of nodes",
             "a cycle through node " + std::to_string(k));
      for (size_t w : walk) state[w] = 1;
    }
  }

  void scenes() {
    // Marks of the roots listed by the scene being checked, cleared after each scene: one array for
    // all scenes (an array per scene would cost scenes x nodes).
    std::vector<bool> listed(parents_.size(), false);
    std::vector<int> marked;
    for (size_t i = 0; i < sizes_["scenes"]; ++i) {
      const json& s = at("scenes", i);
      const std::string p = "/scenes/" + std::to_string(i);
      const json* ns = opt(s, "nodes");
      if (!ns) continue;
      if (!ns->is_array()) bad(p + "/nodes", "an array of root node indices", *ns);
      for (int nd : marked) listed[size_t(nd)] = false;
      marked.clear();
      for (size_t k = 0; k < ns->size(); ++k) {
        const std::string np = p + "/nodes/" + std::to_string(k);
        const int nd = index_value((*ns)[k], np, "nodes");
        if (parents_[nd] >= 0)
          fail(src_, np, "a root node",
               "node " + std::to_string(nd) + ", a child of node " + std::to_string(parents_[nd]));
        if (listed[size_t(nd)]) fail(src_, np, "each root node once", "node " + std::to_string(nd) + " again");
        listed[size_t(nd)] = true;  // the spec requires each root once per scene
        marked.push_back(nd);
      }
    }
    index(doc_, "scene", "", "scenes", false);
  }

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

}  // namespace

void validate_document(const nlohmann::json& doc, const Container& container, const Source& src) {
  Validator(doc, container, src).run();
}

}  // namespace welkin::assets::detail
