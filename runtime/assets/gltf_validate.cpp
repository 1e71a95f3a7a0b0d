// Validation of the glTF JSON before tinygltf sees it: tinygltf trusts indices and ranges in places
// (image bufferViews, Draco streams), substitutes defaults for mistyped values and only warns about
// missing files, so everything the loader relies on is checked here, with the JSON path of the culprit.
#include <algorithm>

#include "gltf_validator.h"

namespace welkin::assets::detail {

void Validator::asset() {
  const json* a = object(doc_, "asset", "");
  if (!a) fail(src_, "/asset", "an object with \"version\": \"2.0\"", "nothing (the property is required)");
  const std::string v = string(*a, "version", "/asset", true);
  if (v.size() < 2 || v[0] != '2' || v[1] != '.')
    fail(src_, "/asset/version", "glTF version \"2.x\"", "\"" + v + "\"");
  const std::string mv = string(*a, "minVersion", "/asset", false);
  if (!mv.empty() && mv != "2.0") fail(src_, "/asset/minVersion", "\"2.0\"", "\"" + mv + "\"");
}

void Validator::extensions() {
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

void Validator::buffers() {
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

void Validator::buffer_views() {
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

void Validator::accessors() {
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
                 " from byteOffset " + std::to_string(offset) + " within bufferView " + std::to_string(view) +
                 " (" + std::to_string(view_lengths_[view]) + " bytes)",
             "a range ending at byte " + std::to_string(end));
    }
    accessors_.push_back(info);
  }
}

void Validator::samplers() {
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

void Validator::images() {
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

void Validator::textures() {
  for (size_t i = 0; i < sizes_["textures"]; ++i) {
    const json& t = at("textures", i);
    const std::string p = "/textures/" + std::to_string(i);
    index(t, "source", p, "images", false);
    index(t, "sampler", p, "samplers", false);
  }
}

void Validator::texture_info(const json& m, const char* key, const std::string& path) {
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

void validate_document(const nlohmann::json& doc, const Container& container, const Source& src) {
  Validator(doc, container, src).run();
}

}  // namespace welkin::assets::detail
