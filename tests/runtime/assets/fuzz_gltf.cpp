// libFuzzer target over the glTF loader: any bytes, as .glb or .gltf, loaded from memory (so no file
// outside the corpus is ever touched). Only welkin::Error may come out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "welkin/assets/gltf_loader.h"
#include "welkin/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  welkin::assets::LoadOptions options;
  // Small limits keep each run fast and memory-bounded; the checks are the same as with the defaults.
  options.limits.max_file_bytes = 1u << 20;
  options.limits.max_vertices_per_primitive = 1u << 16;
  options.limits.max_indices_per_primitive = 3u << 16;
  options.limits.max_total_vertices = 1u << 18;
  options.limits.max_total_indices = 3u << 18;
  options.limits.max_image_pixels = 1u << 20;
  options.limits.max_image_side = 2048;
  options.limits.max_total_image_bytes = 16u << 20;
  const bool glb = size > 0 && (data[0] & 1);  // the name decides how non-GLB bytes are reported
  try {
    const auto model =
        welkin::assets::load_gltf_memory(std::span(data, size), glb ? "fuzz.glb" : "fuzz.gltf", "", options);
    for (const auto& mesh : model.meshes)  // what a renderer would do with it must be safe too
      for (const auto& p : mesh.primitives)
        for (uint32_t i : p.indices)
          if (i >= p.positions.size()) std::abort();
  } catch (const welkin::Error&) {
  }
  return 0;
}
