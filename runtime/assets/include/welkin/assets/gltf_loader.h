#pragma once
// glTF 2.0 loading (.gltf with external or data: buffers and images, and .glb) with
// KHR_draco_mesh_compression, KHR_mesh_quantization and KHR_texture_transform. Files are untrusted:
// every index, range and count is checked before use, external files may only lie in the file's own
// folder (or below it), and every failure is one welkin::Error naming the file and the JSON path.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "welkin/assets/model.h"

namespace welkin::assets {

// Upper bounds for untrusted files; a file over any of them is refused with an Error naming the limit.
// The defaults admit any asset this engine ships (the terrain has ~1.1 M vertices) with wide margin
// while keeping the worst case of one load to a few GiB.
struct LoadLimits {
  uint64_t max_file_bytes = 512ull << 20;  // .glb/.gltf and each external buffer or image file
  uint64_t max_json_bytes = 64ull << 20;   // JSON text (the .gltf or the GLB JSON chunk)
  int max_json_depth = 64;                 // nesting of [ and {; glTF itself needs < 10
  uint32_t max_array_elements = 1u << 16;  // entries of any top-level array (nodes, accessors...)
  uint32_t max_primitives_per_mesh = 4096;
  uint64_t max_vertices_per_primitive = 1u << 24;
  uint64_t max_indices_per_primitive = 3u << 24;
  uint64_t max_total_vertices = 1u << 25;  // summed over all primitives
  uint64_t max_total_indices = 3u << 25;
  int max_image_side = 16384;                   // pixels
  uint64_t max_image_pixels = 1u << 26;         // one image (256 MiB as RGBA8)
  uint64_t max_total_image_bytes = 1ull << 30;  // all decoded images together
  // Draco decodes in a child process with this budget, plus the per-element terms times the faces
  // and vertices its header declares (Draco trusts counts deep inside a stream; Welkin cannot check
  // them without decoding).
  double draco_seconds = 2.0;
  double draco_seconds_per_element = 2e-6;
  uint64_t draco_memory_bytes = 256ull << 20;
  uint64_t draco_memory_bytes_per_element = 512;
};

struct LoadOptions {
  LoadLimits limits;
  bool decode_images = true;  // false: images keep name, mime type and encoded_hash, but no pixels
  // false: meshes keep their names but no primitives, and Draco does not run; for a user that keeps
  // what it builds from the geometry elsewhere, keyed by Model::content_hash.
  bool decode_meshes = true;
};

// Loads `path` (.glb when it starts with the GLB magic, JSON otherwise). Throws welkin::Error.
Model load_gltf(const std::string& path, const LoadOptions& options = {});

// Loads from bytes. `name` is used in errors; external URIs resolve against `base_dir` and are
// refused when it is empty (fuzzing, network input).
Model load_gltf_memory(std::span<const uint8_t> bytes, const std::string& name,
                       const std::string& base_dir = "", const LoadOptions& options = {});

}  // namespace welkin::assets
