// The single translation unit that compiles tinygltf, with file access routed through the loader.
#include <fstream>  // tinygltf's writer needs it and TINYGLTF_NO_FS drops the include
#define TINYGLTF_IMPLEMENTATION
#include "internal.h"
#include "tinygltf_config.h"

namespace welkin::assets::detail {

namespace {

bool file_exists(const std::string& path, void* user) {
  const Source& src = *static_cast<const Source*>(user);
  std::error_code ec;
  return inside_base(src, path) && std::filesystem::is_regular_file(path, ec);
}

std::string expand_path(const std::string& path, void*) {
  return path;
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const Source& src = *static_cast<const Source*>(user);
  if (!inside_base(src, path)) {
    if (err) *err += "refused to read " + path + " (outside the glTF's folder)\n";
    return false;
  }
  try {
    *out = read_file_limited(src, path, src.options.limits.max_file_bytes, "");
    return true;
  } catch (const Error& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files\n";
  return false;
}

// Keeps the encoded bytes of data: URI images for image_decode.cpp; bufferView images are decoded
// from the (validated) bufferView later, so their bytes are not copied here.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  image->image.assign(bytes, bytes + size);
  image->bits = 0;  // marks `image` as still encoded
  return true;
}

}  // namespace

void parse_with_tinygltf(tinygltf::Model& out, std::span<const uint8_t> bytes, const Container& container,
                         const Source& src) {
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_path, &read_whole_file, &write_whole_file,
                                              const_cast<Source*>(&src)});
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  std::string err, warn;
  const std::string base = src.base_dir.empty() ? std::string("/nonexistent-welkin-base") : src.base_dir;
  bool ok = false;
  if (container.is_glb)
    ok = loader.LoadBinaryFromMemory(&out, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
  else
    ok = loader.LoadASCIIFromString(&out, &err, &warn, container.json.data(), unsigned(container.json.size()),
                                    base);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    throw Error(ErrorInfo{.file = src.name, .message = "tinygltf could not parse the file: " + err});
  }
}

}  // namespace welkin::assets::detail
