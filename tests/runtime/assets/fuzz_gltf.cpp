// libFuzzer target over the glTF loader: any bytes, as .glb or .gltf, loaded from memory with a
// scratch folder as the glTF's own folder, so external URIs resolve to real files: a buffer, an
// image, an empty file, a folder and a FIFO (which must be refused without blocking). The loader
// keeps every URI inside that folder; nothing else on disk is read. Only welkin::Error may come out;
// anything else is a bug.
#include <sys/stat.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "welkin/assets/gltf_loader.h"
#include "welkin/core/error.h"

namespace {

std::string g_folder;  // the glTF's folder: the files its URIs may name

void write_bytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  namespace fs = std::filesystem;
  std::string pattern = (fs::temp_directory_path() / "welkin-fuzz-gltf.XXXXXX").string();
  if (!mkdtemp(pattern.data())) std::abort();
  g_folder = pattern;
  const fs::path dir(g_folder);
  // buffer.bin: three float vertices of a triangle, then its indices (uint16 and uint32), then a ramp.
  std::vector<uint8_t> buffer;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t i16[4] = {0, 1, 2, 0};
  const uint32_t i32[3] = {0, 1, 2};
  const auto append = [&buffer](const void* p, size_t n) {
    buffer.insert(buffer.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
  };
  append(positions, sizeof positions), append(i16, sizeof i16), append(i32, sizeof i32);
  for (int i = 0; i < 1024; ++i) buffer.push_back(uint8_t(i));
  write_bytes(dir / "buffer.bin", buffer);
  // image.png: a 1 x 1 grey PNG.
  write_bytes(dir / "image.png",
              {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
               0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a, 0x7e, 0x9b, 0x55, 0x00, 0x00, 0x00,
               0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68, 0x00, 0x00, 0x00, 0x82, 0x00, 0x81, 0x77, 0xcd, 0x72,
               0xb6, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82});
  write_bytes(dir / "empty.bin", {});
  fs::create_directory(dir / "dir");
  if (mkfifo((dir / "fifo.bin").c_str(), 0600) != 0) std::abort();
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(g_folder, ec);
  });
  return 0;
}

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
        welkin::assets::load_gltf_memory(std::span(data, size), glb ? "fuzz.glb" : "fuzz.gltf", g_folder, options);
    for (const auto& mesh : model.meshes)  // what a renderer would do with it must be safe too
      for (const auto& p : mesh.primitives)
        for (uint32_t i : p.indices)
          if (i >= p.positions.size()) std::abort();
  } catch (const welkin::Error&) {
  }
  return 0;
}
