#include "welkin/assets/gltf_loader.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "test_util.h"
#include "welkin/core/disk_cache.h"
#include "welkin/gfx/image.h"

namespace welkin::assets::test {
namespace {

using nlohmann::json;

std::vector<uint8_t> png_bytes(int w, int h) {
  ImageU8 img;
  img.width = w;
  img.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.rgba.insert(img.rgba.end(), {uint8_t(x * 40), uint8_t(y * 80), 7, 255});
  return encode_png(img);
}

// A textured 8 x 8 grid under a translated child node: 81 vertices, 128 triangles.
GlbWriter textured_grid(bool draco) {
  GlbWriter w;
  const int image = w.add_image(png_bytes(4, 2), "image/png", "checker");
  Material mat;
  mat.name = "ground";
  mat.base_color_factor = {0.5f, 0.25f, 1.0f, 1.0f};
  mat.roughness_factor = 0.75f;
  mat.base_color.texture = w.add_texture(image);
  mat.base_color.transform =
      TextureTransform{.present = true, .offset = {0.5f, 0.0f}, .rotation = 0.0f, .scale = {2.0f, 2.0f}};
  MeshData mesh = grid_mesh(8);
  mesh.material = w.add_material(mat);
  const WrittenMesh wm = w.add_mesh(mesh, DracoSettings{.enabled = draco});
  const int root = w.add_node("root", -1, {100.0f, 0.0f, 0.0f});
  w.add_node("grid", wm.mesh, {0.0f, 5.0f, 0.0f}, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(1.0f), root);
  return w;
}

Model load_bytes(const std::string& bytes, const std::string& name = "mem.glb", const LoadOptions& o = {}) {
  return load_gltf_memory(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()), name, "",
                          o);
}

ErrorInfo memory_error(const std::string& bytes, const std::string& name = "bad.glb",
                       const LoadOptions& o = {}) {
  return error_of([&] { load_bytes(bytes, name, o); });
}

ErrorInfo file_error(const fs::path& p, const LoadOptions& o = {}) {
  return error_of([&] { load_gltf(p.string(), o); });
}

void expect_grid(const Model& m, bool draco) {
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), 1u);
  const Primitive& p = m.meshes[0].primitives[0];
  EXPECT_EQ(p.positions.size(), 81u);
  EXPECT_EQ(p.triangle_count(), 128u);
  EXPECT_EQ(p.normals.size(), 81u);
  EXPECT_EQ(p.uv0.size(), 81u);
  EXPECT_FALSE(p.normals_generated);
  EXPECT_EQ(p.draco, draco);
  EXPECT_EQ(m.vertex_count(), 81u);
  EXPECT_EQ(m.triangle_count(), 128u);
  ASSERT_EQ(m.nodes.size(), 2u);
  EXPECT_EQ(m.nodes[1].parent, 0);
  EXPECT_EQ(m.scene_roots, std::vector<int>{0});
  const float tol = draco ? 2e-3f : 1e-6f;  // 14-bit positions over 10 m
  EXPECT_NEAR(m.bounds.min.x, 95.0f, tol);
  EXPECT_NEAR(m.bounds.max.x, 105.0f, tol);
  EXPECT_NEAR(m.bounds.min.z, -5.0f, tol);
  EXPECT_GT(m.bounds.min.y, 4.7f);
  EXPECT_LT(m.bounds.max.y, 5.3f);
  ASSERT_EQ(m.materials.size(), 1u);
  const Material& mat = m.materials[0];
  EXPECT_EQ(mat.name, "ground");
  EXPECT_FLOAT_EQ(mat.base_color_factor.g, 0.25f);
  EXPECT_FLOAT_EQ(mat.roughness_factor, 0.75f);
  ASSERT_TRUE(mat.base_color.valid());
  EXPECT_TRUE(mat.base_color.transform.present);
  EXPECT_FLOAT_EQ(mat.base_color.transform.scale.x, 2.0f);
  EXPECT_FLOAT_EQ(mat.base_color.transform.offset.x, 0.5f);
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].width, 4);
  EXPECT_EQ(m.images[0].height, 2);
  EXPECT_EQ(m.images[0].rgba[(1 * 4 + 3) * 4 + 0], 120);  // pixel (3, 1)
  EXPECT_EQ(m.images[0].rgba[(1 * 4 + 3) * 4 + 1], 80);
  EXPECT_EQ(m.textures.at(size_t(mat.base_color.texture)).image, 0);
  for (uint32_t i : p.indices) ASSERT_LT(i, p.positions.size());
}

TEST(GltfLoader, SmallGlbLoadsWithExactCounts) {
  const fs::path f = temp_dir() / "grid.glb";
  textured_grid(false).write(f.string());
  const Model m = load_gltf(f.string());
  expect_grid(m, false);
  EXPECT_EQ(m.file, f.string());
  EXPECT_EQ(m.extensions_used, std::vector<std::string>{"KHR_texture_transform"});
  // Uncompressed data comes back exactly.
  const MeshData src = grid_mesh(8);
  EXPECT_EQ(m.meshes[0].primitives[0].positions[17], src.positions[17]);
  EXPECT_EQ(m.meshes[0].primitives[0].indices, src.indices);
}

// An emissive strength other than 1 is written (KHR_materials_emissive_strength) and read back: the
// writer used to drop it, and the material came back 4000 times dimmer.
TEST(GltfLoader, EmissiveStrengthIsWrittenAndRead) {
  GlbWriter w;
  Material mat;
  mat.emissive_factor = {0.5f, 1.0f, 0.25f};
  mat.emissive_strength = 4000.0f;
  MeshData mesh = grid_mesh(2);
  mesh.material = w.add_material(mat);
  w.add_node("grid", w.add_mesh(mesh).mesh);
  const Model m = load_bytes(w.glb());
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].emissive_factor, mat.emissive_factor);
  EXPECT_FLOAT_EQ(m.materials[0].emissive_strength, 4000.0f);
  EXPECT_EQ(m.extensions_used, std::vector<std::string>{"KHR_materials_emissive_strength"});
}

TEST(GltfLoader, DracoGlbLoadsWithExactCounts) {
  GlbWriter w = textured_grid(true);
  const Model m = load_bytes(w.glb());
  expect_grid(m, true);
  EXPECT_NE(
      std::find(m.extensions_required.begin(), m.extensions_required.end(), "KHR_draco_mesh_compression"),
      m.extensions_required.end());
  // Draco reorders vertices: compare geometry through the total area instead.
  auto area = [](const std::vector<glm::vec3>& p, const std::vector<uint32_t>& ix) {
    double a = 0;
    for (size_t t = 0; t < ix.size(); t += 3)
      a += 0.5 * glm::length(glm::cross(p[ix[t + 1]] - p[ix[t]], p[ix[t + 2]] - p[ix[t]]));
    return a;
  };
  const MeshData src = grid_mesh(8);
  const Primitive& p = m.meshes[0].primitives[0];
  EXPECT_NEAR(area(p.positions, p.indices), area(src.positions, src.indices), 1e-2);
}

TEST(GltfLoader, ThirdPartyDracoGlbLoads) {
  // Written by gltf-pipeline (draco3d encoder); see data/README.md.
  const Model m = load_gltf(WELKIN_SOURCE_DIR "/tests/runtime/assets/data/grid-draco-gltf-pipeline.glb");
  ASSERT_EQ(m.meshes.size(), 1u);
  const Primitive& p = m.meshes[0].primitives[0];
  EXPECT_TRUE(p.draco);
  EXPECT_EQ(p.positions.size(), 49u);
  EXPECT_EQ(p.triangle_count(), 72u);
  EXPECT_EQ(p.uv0.size(), 49u);
  EXPECT_FALSE(p.normals_generated);
  for (const glm::vec3& n : p.normals) EXPECT_NEAR(n.y, 1.0f, 1e-2f);
  EXPECT_EQ(m.materials.at(0).name, "green");
  EXPECT_NEAR(m.bounds.min.x, -2.0f, 5e-3f);
  EXPECT_NEAR(m.bounds.max.z, 2.0f, 5e-3f);
  EXPECT_GT(m.bounds.min.y, 0.8f);  // node translated by +1
}

// The third-party grid with one count inside its Draco attribute data (past the header Welkin reads)
// raised from a small value to 2^21 - 1 (a 3-byte varint over 2 bytes; the stream grows by one byte
// into the BIN chunk's padding). Draco 1.5.5 then spends about 9 s of CPU and 260 MiB before it
// fails, whatever the mesh's declared size: the class of input the glTF fuzzer found.
std::string grid_with_hostile_draco_count() {
  std::string glb = read_bytes(WELKIN_SOURCE_DIR "/tests/runtime/assets/data/grid-draco-gltf-pipeline.glb");
  const size_t json_length = 1180, stream_at = 20 + json_length + 8, count_at = 431;
  const size_t view_length = glb.find("\"byteLength\":459");
  if (glb.size() != 1672 || view_length == std::string::npos || view_length > 20 + json_length) return {};
  glb.replace(view_length, 16, "\"byteLength\":460");
  glb.replace(stream_at + count_at, 2, "\xff\xff\x7f");
  glb.erase(stream_at + 460, 1);  // one byte less padding: the BIN chunk keeps its length
  return glb;
}

TEST(GltfLoader, DracoDecodeIsBoundedInTimeAndMemory) {
  const std::string glb = grid_with_hostile_draco_count();
  ASSERT_EQ(glb.size(), 1672u);
  // The budget a 49-vertex grid gets by default; its own decode takes a millisecond.
  const ErrorInfo e = memory_error(glb, "hostile.glb");
  EXPECT_EQ(e.file, "hostile.glb");
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression");
  EXPECT_NE(e.found.find("s of CPU time"), std::string::npos) << e.found;
  // Under a memory budget smaller than what Draco reaches for, the same stream fails on memory.
  LoadOptions small;
  small.limits.draco_seconds = 60.0;
  small.limits.draco_memory_bytes = 64ull << 20;
  const ErrorInfo m = memory_error(glb, "hostile.glb", small);
  EXPECT_NE(m.found.find("MiB of memory"), std::string::npos) << m.found;
  // The untouched grid decodes in the child process exactly as before (the same bytes back).
  const Model ok = load_gltf(WELKIN_SOURCE_DIR "/tests/runtime/assets/data/grid-draco-gltf-pipeline.glb");
  EXPECT_EQ(ok.meshes.at(0).primitives.at(0).positions.size(), 49u);
}

// An error the decoding process finds (an attribute id the stream lacks) comes back as one error at
// that attribute's path.
TEST(GltfLoader, DracoErrorFromTheDecodingProcessKeepsItsPath) {
  std::string glb = read_bytes(WELKIN_SOURCE_DIR "/tests/runtime/assets/data/grid-draco-gltf-pipeline.glb");
  const size_t at = glb.find("\"TEXCOORD_0\":2}");
  ASSERT_NE(at, std::string::npos);
  glb.replace(at, 15, "\"TEXCOORD_0\":7}");
  const ErrorInfo e = memory_error(glb, "ids.glb");
  EXPECT_EQ(e.file, "ids.glb");
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression/attributes/TEXCOORD_0");
  EXPECT_EQ(e.found, "7");
}

// The textured grid as a .gltf in `dir` with its buffer in grid.bin and its image, `png`, in the file
// `image_file` (relative to dir) that the document names by `image_uri`. Returns the .gltf's path.
fs::path write_external_grid(const fs::path& dir, const fs::path& image_file, const std::string& image_uri,
                             const std::vector<uint8_t>& png) {
  GlbWriter w = textured_grid(false);
  json doc = w.document();
  write_bytes(dir / "grid.bin", std::string(w.bin().begin(), w.bin().end()));
  doc["buffers"] = json::array({json{{"uri", "grid.bin"}, {"byteLength", w.bin().size()}}});
  fs::create_directories((dir / image_file).parent_path());
  write_bytes(dir / image_file, std::string(png.begin(), png.end()));
  doc["images"][0] = json{{"uri", image_uri}};
  write_bytes(dir / "grid.gltf", doc.dump(2));
  return dir / "grid.gltf";
}

TEST(GltfLoader, GltfWithExternalFilesBesideIt) {
  // The image in a file in a subfolder, referenced with a percent-encoded space.
  const fs::path gltf = write_external_grid(temp_dir("external"), "tex dir/checker.png", "tex%20dir/checker.png", png_bytes(4, 2));
  const Model m = load_gltf(gltf.string());
  expect_grid(m, false);
}

// Without its geometry a file keeps its materials, images and nodes, its meshes keep their names,
// and Draco does not run; the content hash is of every file read, so it follows a change in an
// external buffer as well as in the file itself.
TEST(GltfLoader, WithoutGeometryKeepsTheRestAndTheContentHashFollowsEveryFile) {
  const fs::path dir = temp_dir("without-geometry");
  GlbWriter w = textured_grid(true);
  const fs::path glb = dir / "grid.glb";
  w.write(glb.string());
  const Model full = load_gltf(glb.string());
  LoadOptions o;
  o.decode_meshes = false;
  const Model bare = load_gltf(glb.string(), o);
  ASSERT_EQ(bare.meshes.size(), full.meshes.size());
  EXPECT_EQ(bare.meshes[0].name, full.meshes[0].name);
  EXPECT_TRUE(bare.meshes[0].primitives.empty());
  EXPECT_FALSE(full.meshes[0].primitives.empty());
  ASSERT_EQ(bare.materials.size(), full.materials.size());
  ASSERT_EQ(bare.images.size(), full.images.size());
  EXPECT_EQ(bare.images[0].rgba, full.images[0].rgba);
  EXPECT_EQ(bare.nodes.size(), full.nodes.size());
  EXPECT_EQ(bare.content_hash, full.content_hash) << "the same bytes were read";
  EXPECT_NE(full.content_hash, 0u);

  // A .gltf with an external buffer: one byte of the buffer changes the hash, and so does the JSON.
  GlbWriter plain = textured_grid(false);
  json doc = plain.document();
  doc["buffers"] = json::array({json{{"uri", "grid.bin"}, {"byteLength", plain.bin().size()}}});
  std::string bin(plain.bin().begin(), plain.bin().end());
  write_bytes(dir / "grid.bin", bin);
  write_bytes(dir / "grid.gltf", doc.dump(2));
  const uint64_t before = load_gltf((dir / "grid.gltf").string(), o).content_hash;
  EXPECT_EQ(load_gltf((dir / "grid.gltf").string(), o).content_hash, before);
  bin[bin.size() / 2] = char(bin[bin.size() / 2] ^ 1);
  write_bytes(dir / "grid.bin", bin);
  const uint64_t buffer_changed = load_gltf((dir / "grid.gltf").string(), o).content_hash;
  EXPECT_NE(buffer_changed, before);
  doc["asset"]["generator"] = "another";
  write_bytes(dir / "grid.gltf", doc.dump(2));
  EXPECT_NE(load_gltf((dir / "grid.gltf").string(), o).content_hash, buffer_changed);
}

// Images keep the hash of their encoded bytes whether or not they are decoded (what the terrain keys
// its compressed images by): an external image is read and hashed even when not decoded, a change to
// it changes its hash and the file's, and a missing one is an error either way.
TEST(GltfLoader, ImagesKeepTheHashOfTheirEncodedBytesDecodedOrNot) {
  const fs::path dir = temp_dir("image-hash");
  const auto png = png_bytes(4, 2);
  const std::string png_text(png.begin(), png.end());
  write_external_grid(dir, "checker.png", "checker.png", png);
  LoadOptions bare;
  bare.decode_images = false;
  const Model decoded = load_gltf((dir / "grid.gltf").string());
  const Model undecoded = load_gltf((dir / "grid.gltf").string(), bare);
  ASSERT_EQ(undecoded.images.size(), 1u);
  EXPECT_TRUE(undecoded.images[0].rgba.empty());
  EXPECT_EQ(undecoded.images[0].encoded_hash, DiskCache::hash(png_text));
  EXPECT_EQ(decoded.images[0].encoded_hash, DiskCache::hash(png_text));
  EXPECT_EQ(undecoded.content_hash, decoded.content_hash) << "the same files were read";
  // Another image in its place: its hash and the file's follow.
  const auto other = png_bytes(4, 3);
  write_bytes(dir / "checker.png", std::string(other.begin(), other.end()));
  const Model changed = load_gltf((dir / "grid.gltf").string(), bare);
  EXPECT_NE(changed.images[0].encoded_hash, undecoded.images[0].encoded_hash);
  EXPECT_NE(changed.content_hash, undecoded.content_hash);
  // Missing, it is an error even when it would not be decoded.
  fs::remove(dir / "checker.png");
  EXPECT_EQ(file_error(dir / "grid.gltf", bare).path, "/images/0/uri");
  // In a GLB the image's bytes are the buffer view's.
  const Model glb = load_bytes(textured_grid(true).glb(), "grid.glb", bare);
  EXPECT_NE(glb.images[0].encoded_hash, DiskCache::hash({}));
  EXPECT_EQ(glb.images[0].encoded_hash, load_bytes(textured_grid(true).glb(), "grid.glb").images[0].encoded_hash);
}

TEST(GltfLoader, MeshQuantizationIsDequantized) {
  GlbWriter w;
  const int16_t pos[] = {-32767, 0, 0, 0, 0, 32767, 0, 0, 32767, 0, 0};  // 3 x VEC3, stride 8
  const uint16_t uv[] = {0, 0, 65535, 0, 0, 65535};
  const uint8_t idx[] = {0, 1, 2, 0};
  json& d = w.document();
  d["extensionsUsed"] = {"KHR_mesh_quantization"};
  d["extensionsRequired"] = {"KHR_mesh_quantization"};
  auto view = [&](const void* data, size_t n, int stride) {
    const size_t off = w.bin().size();
    w.bin().insert(w.bin().end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + n);
    while (w.bin().size() % 4) w.bin().push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", off}, {"byteLength", n}};
    if (stride) v["byteStride"] = stride;
    d["bufferViews"].push_back(v);
    return int(d["bufferViews"].size()) - 1;
  };
  d["accessors"] = json::array();
  d["accessors"].push_back({{"bufferView", view(pos, sizeof pos, 8)},
                            {"componentType", 5122},
                            {"normalized", true},
                            {"type", "VEC3"},
                            {"count", 3}});
  d["accessors"].push_back({{"bufferView", view(uv, sizeof uv, 0)},
                            {"componentType", 5123},
                            {"normalized", true},
                            {"type", "VEC2"},
                            {"count", 3}});
  d["accessors"].push_back(
      {{"bufferView", view(idx, 3, 0)}, {"componentType", 5121}, {"type", "SCALAR"}, {"count", 3}});
  json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}};
  d["meshes"] = json::array({json{{"primitives", json::array({prim})}}});
  w.add_node("q", 0, glm::vec3(0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(100.0f));
  const Model m = load_bytes(w.glb());
  const Primitive& p = m.meshes[0].primitives[0];
  ASSERT_EQ(p.positions.size(), 3u);
  EXPECT_FLOAT_EQ(p.positions[0].x, -1.0f);
  EXPECT_FLOAT_EQ(p.positions[1].y, 1.0f);
  EXPECT_FLOAT_EQ(p.uv0[1].x, 1.0f);
  EXPECT_TRUE(p.normals_generated);
  EXPECT_NEAR(m.bounds.min.x, -100.0f, 1e-3f);  // node scale undoes the quantization
  EXPECT_NEAR(m.bounds.max.y, 100.0f, 1e-3f);
  // Without the extension the same accessor is invalid glTF.
  d.erase("extensionsUsed");
  d.erase("extensionsRequired");
  const ErrorInfo e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/attributes/POSITION");
  EXPECT_NE(e.expected.find("KHR_mesh_quantization"), std::string::npos);
}

TEST(GltfLoader, StripsAndFansBecomeTriangleLists) {
  GlbWriter w = textured_grid(false);
  w.document()["meshes"][0]["primitives"][0]["mode"] = 5;  // 648 indices as a strip: 646 triangles
  const Model m = load_bytes(w.glb());
  EXPECT_EQ(m.meshes[0].primitives[0].triangle_count(), 128u * 3 - 2);
  w.document()["meshes"][0]["primitives"][0]["mode"] = 1;  // lines: skipped with a warning
  const Model lines = load_bytes(w.glb());
  EXPECT_TRUE(lines.meshes[0].primitives.empty());
  ASSERT_EQ(lines.warnings.size(), 1u);
  EXPECT_NE(lines.warnings[0].find("/meshes/0/primitives/0"), std::string::npos);
}

// --- Malformed files: each is one clear error naming the file and where. ---

TEST(GltfLoaderErrors, TruncatedGlb) {
  const std::string good = textured_grid(false).glb();
  const fs::path f = temp_dir() / "truncated.glb";
  write_bytes(f, good.substr(0, good.size() - 100));
  const ErrorInfo e = file_error(f);
  EXPECT_EQ(e.file, f.string());
  EXPECT_EQ(e.path, "<glb header>/length");
  EXPECT_NE(e.found.find("truncated"), std::string::npos);
  for (size_t n : {0, 3, 11, 19})
    EXPECT_EQ(memory_error(good.substr(0, n)).path.substr(0, 12), "<glb header>") << n;
}

TEST(GltfLoaderErrors, BadMagic) {
  std::string bytes = textured_grid(false).glb();
  bytes[3] = 'X';
  const fs::path f = temp_dir() / "magic.glb";
  write_bytes(f, bytes);
  const ErrorInfo e = file_error(f);
  EXPECT_EQ(e.path, "<glb header>");
  EXPECT_EQ(e.found, "67 6c 54 58");
  bytes = textured_grid(false).glb();
  bytes[4] = 1;  // version 1
  EXPECT_EQ(memory_error(bytes).path, "<glb header>/version");
}

TEST(GltfLoaderErrors, ChunkLengthLies) {
  const std::string good = textured_grid(false).glb();
  std::string json_lie = good;
  const uint32_t huge = 0x7fffff00;
  std::memcpy(&json_lie[12], &huge, 4);
  EXPECT_EQ(memory_error(json_lie).path, "<glb chunk 0>/length");
  uint32_t json_len;
  std::memcpy(&json_len, &good[12], 4);
  std::string bin_lie = good;
  const uint32_t bin_len = uint32_t(good.size() - 20 - json_len - 8 + 4);
  std::memcpy(&bin_lie[20 + json_len], &bin_len, 4);
  EXPECT_EQ(memory_error(bin_lie).path, "<glb chunk 1>/length");
  std::string bin_type = good;
  bin_type[20 + json_len + 4] = 'X';
  EXPECT_EQ(memory_error(bin_type).path, "<glb chunk 1>/type");
  // The buffer claims more than the BIN chunk holds.
  GlbWriter w = textured_grid(false);
  json doc = w.document();
  doc["buffers"] = json::array({json{{"byteLength", w.bin().size() + 64}}});
  const ErrorInfo e = memory_error(GlbWriter::assemble(doc, w.bin()));
  EXPECT_EQ(e.path, "/buffers/0/byteLength");
}

TEST(GltfLoaderErrors, JsonSyntaxError) {
  const fs::path f = temp_dir() / "syntax.gltf";
  write_bytes(f, "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {\"name\": \"a\"}, ]}");
  const ErrorInfo e = file_error(f);
  EXPECT_EQ(e.file, f.string());
  EXPECT_EQ(e.expected, "valid JSON");
  EXPECT_NE(e.found.find("byte"), std::string::npos);
  // Not an object, no asset, wrong version.
  EXPECT_EQ(memory_error("[1, 2, 3]", "a.gltf").expected, "a JSON object at the top level");
  EXPECT_EQ(memory_error("{\"nodes\": []}", "a.gltf").path, "/asset");
  EXPECT_EQ(memory_error("{\"asset\": {\"version\": \"1.0\"}}", "a.gltf").path, "/asset/version");
  // A key twice in one object is refused (a JSON parser would keep one of them, silently).
  const ErrorInfo twice = memory_error("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 0, \"mesh\": 1}]}", "a.gltf");
  EXPECT_EQ(twice.path, "/nodes/0/mesh");
  EXPECT_EQ(twice.found, "a duplicate key");
}

TEST(GltfLoaderErrors, DeepNestingIsRefusedBeforeParsing) {
  const std::string deep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
  const ErrorInfo e = memory_error(deep, "deep.gltf");
  EXPECT_NE(e.expected.find("nested at most 64"), std::string::npos);
}

TEST(GltfLoaderErrors, AccessorOutOfBufferViewRange) {
  GlbWriter w = textured_grid(false);
  w.document()["accessors"][0]["count"] = 82;  // POSITION: one element more than its view holds
  ErrorInfo e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/accessors/0");
  EXPECT_NE(e.expected.find("within bufferView"), std::string::npos);
  w = textured_grid(false);
  w.document()["accessors"][1]["byteOffset"] = 4;
  EXPECT_EQ(memory_error(w.glb()).path, "/accessors/1");
  w = textured_grid(false);
  w.document()["bufferViews"][1]["byteLength"] = 1 << 20;  // view past the buffer
  EXPECT_EQ(memory_error(w.glb()).path, "/bufferViews/1/byteLength");
  w = textured_grid(false);
  w.document()["images"][0]["bufferView"] = 99;
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/images/0/bufferView");
  EXPECT_EQ(e.found, "99");
}

TEST(GltfLoaderErrors, IndexOutOfRange) {
  GlbWriter w = textured_grid(false);
  uint32_t* idx = reinterpret_cast<uint32_t*>(w.bin().data() +
                                              w.document()["bufferViews"][4]["byteOffset"].get<size_t>());
  idx[5] = 81;
  const ErrorInfo e = memory_error(w.glb(), "idx.glb");
  EXPECT_EQ(e.file, "idx.glb");
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/indices");
  EXPECT_EQ(e.found, "index 81 at element 5");
  // Index references to missing objects.
  w = textured_grid(false);
  w.document()["meshes"][0]["primitives"][0]["material"] = 3;
  EXPECT_EQ(memory_error(w.glb()).path, "/meshes/0/primitives/0/material");
  w = textured_grid(false);
  w.document()["nodes"][1]["mesh"] = -1;
  EXPECT_EQ(memory_error(w.glb()).path, "/nodes/1/mesh");
  w = textured_grid(false);
  w.document()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = "x";
  EXPECT_EQ(memory_error(w.glb()).path, "/meshes/0/primitives/0/attributes/NORMAL");
}

TEST(GltfLoaderErrors, DracoStreamWithFewerVerticesThanAccessor) {
  GlbWriter w = textured_grid(true);
  for (int a : {0, 1, 2}) w.document()["accessors"][a]["count"] = 100;  // the stream decodes to 81
  ErrorInfo e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/attributes/NORMAL");  // attributes are checked in name order
  EXPECT_EQ(e.expected, "100 vertices (accessor 1 count)");
  EXPECT_EQ(e.found, "81 decoded by Draco");
  // A corrupt stream and an unknown attribute id are errors too, not silently kept bytes.
  w = textured_grid(true);
  const size_t off = w.document()["bufferViews"][1]["byteOffset"].get<size_t>();
  w.bin()[off] = 'X';  // "DRACO" magic
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression");
  EXPECT_NE(e.found.find("bad header"), std::string::npos);
  w = textured_grid(true);
  w.document()["bufferViews"][1]["byteLength"] = 40;  // the stream cut short
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression");
  w = textured_grid(true);
  w.document()["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]
              ["NORMAL"] = 7;
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression/attributes/NORMAL");
  w = textured_grid(true);
  w.document()["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 9;
  EXPECT_EQ(memory_error(w.glb()).path,
            "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression/bufferView");
}

TEST(GltfLoaderErrors, UriEscapingTheFolder) {
  const fs::path dir = temp_dir("uris/inner");
  write_bytes(dir.parent_path() / "outside.bin", std::string(64, '\0'));
  auto gltf_with_uri = [&](const std::string& uri, const char* what = "buffers") {
    json doc = {{"asset", {{"version", "2.0"}}}};
    if (std::string(what) == "buffers")
      doc["buffers"] = {{{"uri", uri}, {"byteLength", 64}}};
    else
      doc["images"] = {{{"uri", uri}}};
    const fs::path f = dir / "u.gltf";
    write_bytes(f, doc.dump());
    return file_error(f);
  };
  ErrorInfo e = gltf_with_uri("../outside.bin");
  EXPECT_EQ(e.path, "/buffers/0/uri");
  EXPECT_NE(e.found.find("\"..\""), std::string::npos);
  EXPECT_NE(gltf_with_uri("%2e%2e/outside.bin").found.find(".."), std::string::npos);
  EXPECT_NE(gltf_with_uri("sub/../../outside.bin").found.find(".."), std::string::npos);
  e = gltf_with_uri((dir.parent_path() / "outside.bin").string());
  EXPECT_NE(e.found.find("absolute path"), std::string::npos);
  e = gltf_with_uri("file:///etc/passwd");
  EXPECT_NE(e.found.find("URI scheme"), std::string::npos);
  e = gltf_with_uri("https://example.com/a.png", "images");
  EXPECT_EQ(e.path, "/images/0/uri");
  EXPECT_NE(e.found.find("URI scheme"), std::string::npos);
  e = gltf_with_uri("data:text/html;base64,AAAA");
  EXPECT_EQ(e.path, "/buffers/0/uri");
  // A symbolic link beside the file that points outside is refused as well.
  fs::remove(dir / "link.bin");
  fs::create_symlink(dir.parent_path() / "outside.bin", dir / "link.bin");
  e = gltf_with_uri("link.bin");
  EXPECT_NE(e.found.find("outside the folder"), std::string::npos);
  // From memory, no external file at all.
  const std::string doc = R"({"asset":{"version":"2.0"},"buffers":[{"uri":"a.bin","byteLength":4}]})";
  EXPECT_NE(memory_error(doc, "mem.gltf").expected.find("loaded from memory"), std::string::npos);
}

TEST(GltfLoaderErrors, MissingExternalFile) {
  const fs::path dir = temp_dir("missing");
  GlbWriter w = textured_grid(false);
  json doc = w.document();
  doc["buffers"] = json::array({json{{"uri", "nope.bin"}, {"byteLength", w.bin().size()}}});
  write_bytes(dir / "m.gltf", doc.dump());
  ErrorInfo e = file_error(dir / "m.gltf");
  EXPECT_EQ(e.file, (dir / "m.gltf").string());
  EXPECT_EQ(e.path, "/buffers/0/uri");
  EXPECT_EQ(e.found, "missing file \"nope.bin\"");
  write_bytes(dir / "nope.bin", std::string(w.bin().begin(), w.bin().end()));
  doc["images"][0] = json{{"uri", "nope.png"}};
  write_bytes(dir / "m.gltf", doc.dump());
  e = file_error(dir / "m.gltf");
  EXPECT_EQ(e.path, "/images/0/uri");
  e = file_error(dir / "does-not-exist.glb");
  EXPECT_EQ(e.found, "no such file");
}

TEST(GltfLoaderErrors, CountLimits) {
  const std::string bytes = textured_grid(false).glb();
  LoadOptions o;
  o.limits.max_vertices_per_primitive = 80;
  ErrorInfo e = memory_error(bytes, "lim.glb", o);
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/attributes");
  EXPECT_EQ(e.expected, "at most 80 vertices");
  o = {};
  o.limits.max_total_vertices = 80;
  e = memory_error(bytes, "lim.glb", o);
  EXPECT_EQ(e.expected, "at most 80 vertices in all meshes");
  o = {};
  o.limits.max_indices_per_primitive = 383;
  EXPECT_EQ(memory_error(bytes, "lim.glb", o).path, "/meshes/0/primitives/0/indices");
  o = {};
  o.limits.max_array_elements = 4;  // 4 accessors pass, 5 bufferViews do not
  e = memory_error(bytes, "lim.glb", o);
  EXPECT_EQ(e.path, "/bufferViews");
  EXPECT_EQ(e.found, "5 entries");
  o = {};
  o.limits.max_image_side = 3;
  e = memory_error(bytes, "lim.glb", o);
  EXPECT_EQ(e.path, "/images/0/bufferView");
  EXPECT_EQ(e.found, "4 x 2");
  o = {};
  o.limits.max_json_bytes = 100;
  EXPECT_EQ(memory_error(bytes, "lim.glb", o).path, "<glb chunk 0>/length");
  o = {};
  o.limits.max_file_bytes = 100;
  EXPECT_NE(memory_error(bytes, "lim.glb", o).expected.find("at most 100 bytes"), std::string::npos);
}

TEST(GltfLoaderErrors, NodeGraphMustBeAForest) {
  GlbWriter w = textured_grid(false);
  w.document()["nodes"][1]["children"] = {0};
  ErrorInfo e = memory_error(w.glb());  // 0 -> 1 -> 0
  EXPECT_NE(e.found.find("cycle"), std::string::npos);
  w = textured_grid(false);
  w.add_node("other", -1);
  w.document()["nodes"][2]["children"] = {1};
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/nodes/2/children/0");
  EXPECT_NE(e.found.find("already a child of node 0"), std::string::npos);
  // The spec requires a scene's roots and a node's children to be unique.
  w = textured_grid(false);
  w.add_node("other", -1);
  w.document()["scenes"][0]["nodes"] = {0, 2, 0};
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/scenes/0/nodes/2");
  EXPECT_EQ(e.found, "node 0 again");
  w = textured_grid(false);
  w.add_node("other", -1);
  w.document()["nodes"][0]["children"] = {1, 1};
  e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/nodes/0/children/1");
  EXPECT_NE(e.found.find("already a child of node 0"), std::string::npos);
}

TEST(GltfLoaderErrors, UnsupportedRequiredExtensionAndBadValues) {
  GlbWriter w = textured_grid(false);
  w.document()["extensionsRequired"] = {"KHR_materials_volume"};
  EXPECT_EQ(memory_error(w.glb()).path, "/extensionsRequired/0");
  w = textured_grid(false);
  w.document()["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 2;
  EXPECT_EQ(memory_error(w.glb()).path, "/materials/0/pbrMetallicRoughness/metallicFactor");
  w = textured_grid(false);
  w.document()["nodes"][0]["translation"] = {1, 2};
  EXPECT_EQ(memory_error(w.glb()).path, "/nodes/0/translation");
  w = textured_grid(false);
  w.document()["accessors"][0]["sparse"] = json::object();
  EXPECT_EQ(memory_error(w.glb()).path, "/accessors/0/sparse");
  w = textured_grid(false);
  w.document()["accessors"][0]["componentType"] = 5124;
  EXPECT_EQ(memory_error(w.glb()).path, "/accessors/0/componentType");
  // A float that overflows to infinity is refused by the JSON parser already.
  const ErrorInfo inf =
      memory_error(R"({"asset":{"version":"2.0"},"nodes":[{"translation":[0,1e999,0]}]})", "inf.gltf");
  EXPECT_EQ(inf.expected, "valid JSON");
  EXPECT_NE(inf.found.find("1e999"), std::string::npos);
}

// Varint as Draco writes it: 7 bits a byte, low bits first.
std::vector<uint8_t> draco_varint(uint32_t v) {
  std::vector<uint8_t> out;
  do {
    out.push_back(uint8_t((v & 0x7f) | (v > 0x7f ? 0x80 : 0)));
    v >>= 7;
  } while (v);
  return out;
}

// The grid's edgebreaker stream with its header's face count replaced: the 11-byte Draco header,
// the traversal type, the encoded vertex count and the face count (varints) lead the stream.
GlbWriter grid_with_draco_faces(uint32_t faces) {
  GlbWriter w = textured_grid(true);
  json& view = w.document()["bufferViews"][1];
  const size_t off = view["byteOffset"].get<size_t>(), len = view["byteLength"].get<size_t>();
  std::vector<uint8_t> stream(w.bin().begin() + off, w.bin().begin() + off + len);
  EXPECT_EQ(stream[8], 1);  // edgebreaker, as GlbWriter encodes
  size_t p = 12;
  while (stream[p] & 0x80) ++p;  // encoded vertices
  const size_t faces_at = ++p;
  while (stream[p] & 0x80) ++p;
  std::vector<uint8_t> crafted(stream.begin(), stream.begin() + faces_at);
  const auto v = draco_varint(faces);
  crafted.insert(crafted.end(), v.begin(), v.end());
  crafted.insert(crafted.end(), stream.begin() + p + 1, stream.end());
  while (w.bin().size() % 4) w.bin().push_back(0);
  view["byteOffset"] = w.bin().size();
  view["byteLength"] = crafted.size();
  w.bin().insert(w.bin().end(), crafted.begin(), crafted.end());
  w.document()["buffers"][0]["byteLength"] = w.bin().size();
  return w;
}

TEST(GltfLoaderErrors, DracoHeaderCountsAreCheckedBeforeDecoding) {
  // The stream as written decodes (the crafting itself changes nothing else).
  EXPECT_NO_THROW(load_bytes(grid_with_draco_faces(128).glb()));
  // A header claiming 2^28 faces: refused from the header, before Draco starts decoding, with the
  // limit named (Draco 1.5.5 itself refuses it later with only "Failed to decode geometry data").
  ErrorInfo e = memory_error(grid_with_draco_faces(1u << 28).glb(), "huge.glb");
  EXPECT_EQ(e.file, "huge.glb");
  EXPECT_EQ(e.path, "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression");
  EXPECT_EQ(e.expected, "at most 50331648 indices");
  EXPECT_EQ(e.found, "805306368 (268435456 faces in the Draco header)");
  // Within the limits but not what the indices accessor declares (384): refused before decoding too.
  e = memory_error(grid_with_draco_faces(200).glb());
  EXPECT_EQ(e.expected, "384 indices (the indices accessor's count)");
  EXPECT_EQ(e.found, "600 (200 faces in the Draco header)");
  // And against lower limits, which the accessors alone would pass.
  LoadOptions o;
  o.limits.max_indices_per_primitive = 300;
  GlbWriter w = grid_with_draco_faces(1000);
  w.document()["accessors"][3]["count"] = 300;
  e = memory_error(w.glb(), "lim.glb", o);
  EXPECT_EQ(e.expected, "at most 300 indices");
  EXPECT_EQ(e.found, "3000 (1000 faces in the Draco header)");
}

// A PNG of `w` x `h` RGBA8 whose IDAT stream inflates to `inflated_mib` MiB of zero bytes (filter
// type 0, black pixels): one deflated MiB of zeros (about 1 KiB, ending on a full flush, so it
// refers to nothing before it) repeated, then an empty final block and the Adler-32 of the whole.
// With `empty_idat_first`, an empty IDAT chunk comes before the data.
std::string png_bomb(uint32_t w, uint32_t h, uint32_t inflated_mib, bool empty_idat_first = false) {
  std::vector<uint8_t> zeros(1 << 20, 0), block(1 << 16);
  z_stream z{};
  EXPECT_EQ(deflateInit(&z, 9), Z_OK);
  z.next_in = zeros.data();
  z.avail_in = uInt(zeros.size());
  z.next_out = block.data();
  z.avail_out = uInt(block.size());
  EXPECT_EQ(deflate(&z, Z_FULL_FLUSH), Z_OK);
  block.resize(block.size() - z.avail_out);
  const size_t header = 2;  // the first call wrote the zlib header before the block
  deflateEnd(&z);
  std::string idat(block.begin(), block.end());
  uLong adler = adler32(0, nullptr, 0);
  for (uint32_t i = 0; i < inflated_mib; ++i) {
    if (i > 0) idat.append(block.begin() + header, block.end());
    adler = adler32(adler, zeros.data(), uInt(zeros.size()));
  }
  idat += std::string("\x03\x00", 2);  // final fixed-Huffman block with only end-of-block
  for (int s = 24; s >= 0; s -= 8) idat += char((adler >> s) & 0xff);
  auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  auto chunk = [&](const char* type, const std::string& data) {
    std::string body = std::string(type, 4) + data;
    const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()));
    return be32(uint32_t(data.size())) + body + be32(uint32_t(crc));
  };
  const std::string ihdr = be32(w) + be32(h) + std::string("\x08\x06\x00\x00\x00", 5);  // RGBA8
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + (empty_idat_first ? chunk("IDAT", "") : "") +
         chunk("IDAT", idat) + chunk("IEND", "");
}

ErrorInfo image_error(const std::string& png, const std::string& name) {
  GlbWriter w;
  w.add_image(std::vector<uint8_t>(png.begin(), png.end()), "image/png", "bomb");
  return memory_error(w.glb(), name);
}

TEST(GltfLoaderErrors, PngInflationIsBoundedByItsHeader) {
  // (Honest PNGs, whose stream is their header's size, still decode: every textured grid here.)
  // About 256 KiB of file inflating to 256 MiB behind a 1024 x 1024 header (4 MiB of scanlines):
  // stopped as soon as inflation passes 4195328 bytes, never holding more than 64 KiB of it. stb
  // alone would inflate all 256 MiB into memory and then decode the first 4 MiB as the image.
  const std::string bomb = png_bomb(1024, 1024, 256);
  EXPECT_LT(bomb.size(), 400u << 10);
  ErrorInfo e = image_error(bomb, "bomb.glb");
  EXPECT_EQ(e.file, "bomb.glb");
  EXPECT_EQ(e.path, "/images/0/bufferView");
  EXPECT_EQ(e.expected, "PNG image data inflating to at most 4195328 bytes (its header's 1024 x 1024)");
  EXPECT_EQ(e.found.rfind("more (stopped after ", 0), 0u);
  // A 1 x 1 header (5 bytes of scanline) with 64 MiB behind it.
  e = image_error(png_bomb(1, 1, 64), "tiny.glb");
  EXPECT_EQ(e.expected, "PNG image data inflating to at most 5 bytes (its header's 1 x 1)");
}

TEST(GltfLoaderErrors, PngWithAnEmptyFirstIdatIsRefused) {
  // stb_image would copy it through a null buffer (undefined behaviour the fuzzer found).
  const ErrorInfo e = image_error(png_bomb(1, 1, 0, true), "empty-idat.glb");
  EXPECT_EQ(e.path, "/images/0/bufferView");
  EXPECT_EQ(e.expected, "PNG image data starting in its first IDAT chunk");
  EXPECT_EQ(e.found, "an empty IDAT chunk before the image data");
}

TEST(GltfLoaderErrors, CorruptImage) {
  GlbWriter w = textured_grid(false);
  const size_t off = w.document()["bufferViews"][0]["byteOffset"].get<size_t>();
  w.bin()[off + 1] = 'X';  // PNG signature broken
  const ErrorInfo e = memory_error(w.glb());
  EXPECT_EQ(e.path, "/images/0/bufferView");
  EXPECT_EQ(e.expected, "a PNG or JPEG image");
  LoadOptions o;
  o.decode_images = false;  // then the image is not looked at
  EXPECT_NO_THROW(load_bytes(w.glb(), "x.glb", o));
}

}  // namespace
}  // namespace welkin::assets::test
