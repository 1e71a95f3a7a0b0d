#pragma once
// Shared between the loader's translation units; not installed.
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/assets/gltf_loader.h"
#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"

namespace tinygltf {
class Model;
}

namespace welkin::assets::detail {

// What one load works from: the name used in errors and where external files may come from.
struct Source {
  std::string name;
  std::string base_dir;  // "" refuses every external URI
  LoadOptions options;
  // FNV-1a chained over every file's bytes as they are read (Model::content_hash).
  mutable uint64_t content_hash = DiskCache::hash({});
};

[[noreturn]] void fail(const Source& src, const std::string& path, const std::string& expected,
                       const std::string& found);

// Bytes per component of a glTF accessor componentType (5120 BYTE .. 5126 FLOAT); 0 for any other.
inline int component_size(int component_type) {
  switch (component_type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

// JSON pointer segment escaping (~ and / in keys such as attribute names).
std::string pointer_key(std::string_view key);

// A JSON value shortened for an error message.
std::string show(const nlohmann::json& value);

// The JSON text and BIN chunk of a .glb, or the whole text of a .gltf.
struct Container {
  bool is_glb = false;
  std::string_view json;
  std::span<const uint8_t> bin;  // empty when the GLB has no BIN chunk
  bool has_bin = false;
};
Container split_container(std::span<const uint8_t> bytes, const Source& src);

// Checks nesting depth before parsing (a recursive parser must never see 100 000 open brackets).
nlohmann::json parse_json(std::string_view text, const Source& src);

// %xx decoding as tinygltf applies it to URIs before opening files.
std::string percent_decode(std::string_view uri);

enum class DataUriKind { none, buffer, image, unsupported };
DataUriKind data_uri_kind(std::string_view uri);
// Size of the base64 payload of a data: URI once decoded (as tinygltf's decoder would produce it).
uint64_t data_uri_decoded_size(std::string_view uri);

// Resolves an external URI beside the glTF file: relative, no "..", no scheme, no absolute path, and
// the canonical result (symlinks followed) still inside the base folder. Throws Error at `path`.
std::filesystem::path resolve_external(const Source& src, const std::string& uri, const std::string& path);
// True when `candidate` (any spelling) canonically lies inside the base folder; never throws.
bool inside_base(const Source& src, const std::filesystem::path& candidate);
// Reads a whole file of at most `max_bytes`. Throws Error at `path`.
// Chains a file's size and bytes into src.content_hash.
void hash_content(const Source& src, std::span<const uint8_t> bytes);
std::vector<uint8_t> read_file_limited(const Source& src, const std::filesystem::path& file,
                                       uint64_t max_bytes, const std::string& path);

// Structure, indices, ranges, counts and URI policy of the whole document; throws the first problem.
void validate_document(const nlohmann::json& doc, const Container& container, const Source& src);

// tinygltf's parse of an already validated document (the only translation unit that compiles it).
void parse_with_tinygltf(tinygltf::Model& out, std::span<const uint8_t> bytes, const Container& container,
                         const Source& src);

// Builds the CPU model from tinygltf's model; `doc` is the validated JSON (for extension objects).
Model convert_model(const tinygltf::Model& gm, const nlohmann::json& doc, const Source& src);

// Draco mesh stream decoded into triangle indices and the float attributes the primitive asked for.
struct DracoAttribute {
  int components = 0;
  std::vector<float> values;  // num_points * components
};
struct DracoMesh {
  uint32_t num_points = 0;
  std::vector<uint32_t> indices;
  std::map<std::string, DracoAttribute> attributes;  // by glTF attribute name
};
// An attribute to read from the stream, converted as its accessor's component type and
// normalization say.
struct DracoRequest {
  std::string name;  // glTF attribute name (POSITION ...)
  int unique_id = 0;
  int components = 0;
  int component_type = 0;
  bool normalized = false;
  std::string path;  // for errors
};
// What the primitive's accessors declare; the stream's header must agree before it is decoded.
struct DracoExpected {
  uint64_t points = 0;   // the attribute accessors' count
  int64_t indices = -1;  // the indices accessor's count, -1 when the primitive has none
  std::vector<DracoRequest> attributes;
};

// Throws Error at `path` when the stream is not a valid triangle mesh, exceeds the limits or
// disagrees with `expected` (its header's counts are checked before decoding), or at a request's
// path when that attribute is missing or unconvertible. Draco itself runs in a child process under
// the time and memory budget the header's counts allow (LoadLimits).
DracoMesh decode_draco(std::span<const uint8_t> stream, const DracoExpected& expected, const Source& src,
                       const std::string& path);

// Decodes PNG or JPEG to RGBA8 after checking its header against the limits.
// `total_bytes` accumulates decoded bytes across images for max_total_image_bytes.
Image decode_image(std::span<const uint8_t> encoded, const Source& src, const std::string& path,
                   uint64_t& total_bytes);

}  // namespace welkin::assets::detail
