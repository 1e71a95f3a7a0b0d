// Writes the fuzz seed corpus: small valid files that reach every part of the loader (GLB, JSON with
// data: buffers, Draco, quantized attributes, textures with transforms, a third-party Draco file).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_meshes.h"
#include "welkin/assets/glb_writer.h"
#include "welkin/gfx/image.h"

namespace fs = std::filesystem;
using namespace welkin::assets;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  auto put = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  };
  welkin::ImageU8 img{
      .width = 2, .height = 2, .rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 255}};
  const fs::path png = dir / "tmp.png";
  welkin::write_png(png.string(), img);
  std::ifstream in(png, std::ios::binary);
  const std::vector<uint8_t> png_bytes((std::istreambuf_iterator<char>(in)), {});
  fs::remove(png);
  for (bool draco : {false, true}) {
    GlbWriter w;
    Material m;
    m.base_color.texture = w.add_texture(w.add_image(png_bytes, "image/png"));
    m.base_color.transform.present = true;
    m.base_color.transform.scale = {2.0f, 3.0f};
    MeshData mesh = test::grid_mesh(3);
    mesh.material = w.add_material(m);
    const int root = w.add_node("root", -1, {1, 2, 3});
    w.add_node("grid", w.add_mesh(mesh, DracoSettings{.enabled = draco}).mesh, {}, {1, 0, 0, 0}, {1, 1, 1},
               root);
    put(draco ? "grid-draco.glb" : "grid.glb", w.glb());
    if (!draco) {  // the same as .gltf with a data: buffer
      nlohmann::json doc = w.document();
      std::string b64;
      const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      const auto& bin = w.bin();
      for (size_t i = 0; i < bin.size(); i += 3) {
        const uint32_t v = uint32_t(bin[i]) << 16 | (i + 1 < bin.size() ? uint32_t(bin[i + 1]) << 8 : 0) |
                           (i + 2 < bin.size() ? bin[i + 2] : 0);
        b64 += t[v >> 18 & 63];
        b64 += t[v >> 12 & 63];
        b64 += i + 1 < bin.size() ? t[v >> 6 & 63] : '=';
        b64 += i + 2 < bin.size() ? t[v & 63] : '=';
      }
      doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + b64}}};
      put("grid.gltf", doc.dump());
      doc["meshes"][0]["primitives"][0]["mode"] = 5;
      put("grid-strip.gltf", doc.dump());
    }
  }
  const fs::path third =
      fs::path(WELKIN_SOURCE_DIR) / "tests/runtime/assets/data/grid-draco-gltf-pipeline.glb";
  std::error_code ec;
  fs::copy_file(third, dir / "gltf-pipeline.glb", fs::copy_options::overwrite_existing, ec);
  // External files (the fuzzer's scratch folder holds buffer.bin and image.png): a triangle from
  // buffer.bin (36 bytes of positions, then uint16 indices) and a texture from image.png.
  put("external.gltf",
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("buffers":[{"uri":"buffer.bin","byteLength":1080}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],)"
      R"("images":[{"uri":"image.png"}],"textures":[{"source":0}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}]})");
  put("minimal.gltf",
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}]})");
  return 0;
}
