#include "terrain_gpu.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>

#include "welkin/assets/block_compression.h"

#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"

namespace welkin::terrain {

namespace {

GlBufferName upload(std::span<const uint8_t> bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, GLsizeiptr(std::max<size_t>(1, bytes.size())),
                       bytes.empty() ? nullptr : bytes.data(), 0);
  return GlBufferName(id);
}

// `v = {}` assigns an empty list and keeps the capacity: an empty vector swapped in gives it back.
template <class T> void release(std::vector<T>& v) { std::vector<T>().swap(v); }

void sampler_parameters(GLuint id, const assets::Sampler& sampler) {
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, sampler.wrap_s);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, sampler.wrap_t);
  // No anisotropic filtering: on llvmpipe it multiplies the cost of every terrain pixel several times.
}

// RGBA8 with the levels made on the CPU (for_each_mip_level): they hold level 0's mean light.
GlTextureName upload_rgba(const assets::Image& img, const assets::Sampler& sampler, bool srgb) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, assets::mip_level_count(img.width, img.height), srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8,
                     img.width, img.height);
  assets::for_each_mip_level(img, srgb, assets::mip_edge_of_gl_wrap(sampler.wrap_s),
                             assets::mip_edge_of_gl_wrap(sampler.wrap_t),
                             [&](int level, int w, int h, const uint8_t* rgba) {
                               glTextureSubImage2D(id, level, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
                             });
  sampler_parameters(id, sampler);
  return GlTextureName(id);
}

GlTextureName upload_bc1(const assets::Bc1Chain& chain, const assets::Sampler& sampler, bool srgb) {
  const GLenum format = srgb ? GL_COMPRESSED_SRGB_S3TC_DXT1_EXT : GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, GLsizei(chain.levels.size()), format, chain.width, chain.height);
  for (size_t l = 0; l < chain.levels.size(); ++l) {
    const assets::Bc1Level& lv = chain.levels[l];
    glCompressedTextureSubImage2D(id, GLint(l), 0, 0, lv.width, lv.height, format, GLsizei(lv.size),
                                  chain.blocks.data() + lv.offset);
  }
  sampler_parameters(id, sampler);
  return GlTextureName(id);
}

// GL 4.5 core does not require S3TC; llvmpipe and desktop GPUs have it (and its sRGB forms).
bool bc1_supported() {
  return epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc") &&
         (epoxy_has_gl_extension("GL_EXT_texture_sRGB") ||
          epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc_srgb"));
}

// The compressed chain of one image as the disk cache keeps it: its size, then its blocks. The key is
// the encoded image's hash with everything else the levels depend on; its version is bumped when the
// levels or the blocks are made differently (mip_levels.cpp, block_compression.cpp).
std::string bc1_cache_key(const assets::Image& img, const assets::Sampler& sampler, bool srgb) {
  char key[96];
  std::snprintf(key, sizeof key, "terrain-bc1-v1|%016llx|%d|%d|%d|",
                static_cast<unsigned long long>(img.encoded_hash), int(srgb), sampler.wrap_s, sampler.wrap_t);
  return key;
}

std::optional<assets::Bc1Chain> read_bc1(const DiskCache& disk, const std::string& key) {
  const auto size = disk.read(key + "size", 2 * sizeof(int32_t));
  if (!size) return std::nullopt;
  int32_t wh[2];
  std::memcpy(wh, size->data(), sizeof wh);
  const assets::LoadLimits limits;
  if (wh[0] < 1 || wh[1] < 1 || wh[0] > limits.max_image_side || wh[1] > limits.max_image_side)
    return std::nullopt;
  assets::Bc1Chain chain = assets::bc1_layout(wh[0], wh[1]);
  auto blocks = disk.read(key + "blocks", chain.levels.back().offset + chain.levels.back().size);
  if (!blocks) return std::nullopt;
  chain.blocks = std::move(*blocks);
  return chain;
}

void write_bc1(const DiskCache& disk, const std::string& key, const assets::Bc1Chain& chain) {
  const int32_t wh[2] = {chain.width, chain.height};
  if (disk.write(key + "blocks", {reinterpret_cast<const char*>(chain.blocks.data()), chain.blocks.size()}))
    disk.write(key + "size", {reinterpret_cast<const char*>(wh), sizeof wh});
}

std::string cache_key(const Terrain& s) {
  return s.file + "|" + std::to_string(s.compress_images) + "|" + std::to_string(s.chunks_per_side) + "|" +
         std::to_string(s.lod_levels) + "|" + std::to_string(s.refine) + "|" +
         std::to_string(s.refine_levels) + "|" + std::to_string(s.refine_max_triangles);
}

}  // namespace

Texture& TerrainCache::shadow_map(int size) {
  if (!shadow_atlas || shadow_atlas->desc().height != size) {
    shadow_atlas = std::make_unique<Texture>(TextureDesc{.width = size * kShadowCascades, .height = size,
                                                        .format = TextureFormat::depth32f});
    // Hardware depth comparison with linear filtering: a 2x2 percentage-closer filter per fetch.
    glTextureParameteri(shadow_atlas->id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(shadow_atlas->id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
  return *shadow_atlas;
}

TerrainCache::LoadedMesh TerrainCache::load_mesh(const Terrain& s, TerrainMesh& mesh) {
  const DiskCache disk = DiskCache::from_environment();
  LoadedMesh loaded;
  if (!disk.enabled()) {
    loaded.model = assets.load(s.file);
    mesh = build_terrain_mesh(*loaded.model, s);
    loaded.arrays = mesh_arrays(mesh);
    return loaded;
  }
  // The file without its geometry (its bytes hashed), then the mesh from the cache when it is there.
  // Compressed images come from the disk cache too: then the images are not decoded either.
  loaded.model = (s.compress_images && bc1_supported() ? assets_bare : assets_without_geometry).load(s.file);
  const std::string key = mesh_cache_key(loaded.model->content_hash, s);
  // A bound before anything is read: far above any terrain this engine admits (assets::LoadLimits).
  constexpr size_t kMaxMeshBytes = size_t(4) << 30;
  std::optional<TerrainMesh> cached;
  if (auto counts = disk.read(key + "counts", 4 * sizeof(uint64_t)))
    if (auto size = mesh_body_size(*counts, kMaxMeshBytes))
      if (auto body = disk.read(key + "body", *size)) {
        loaded.body = std::move(*body);
        cached = mesh_from_bytes(*counts, loaded.body, loaded.arrays);
      }
  const size_t materials = loaded.model->materials.size();
  if (cached && std::all_of(cached->chunks.begin(), cached->chunks.end(),
                            [&](const Chunk& c) { return c.material < int(materials); })) {
    mesh = std::move(*cached);
    ++mesh_cache_reads;
    return loaded;
  }
  // A miss: the whole file read again, and the mesh, its materials and its key all taken from that one
  // read (the file may have changed since the first).
  release(loaded.body);
  loaded.model.reset();
  assets_without_geometry.evict_unused();
  assets_bare.evict_unused();
  loaded.model = assets.load(s.file);
  mesh = build_terrain_mesh(*loaded.model, s);
  loaded.arrays = mesh_arrays(mesh);
  const std::string built_key = mesh_cache_key(loaded.model->content_hash, s);
  if (mesh.normals.size() == mesh.positions.size() && mesh.uvs.size() == mesh.positions.size() &&
      disk.write(built_key + "body", mesh_body_bytes(mesh)))
    disk.write(built_key + "counts", mesh_counts_bytes(mesh));
  return loaded;
}

GpuTerrain& TerrainCache::get(const Terrain& s) {
  auto& slot = terrains[cache_key(s)];
  if (slot) return *slot;
  if (s.file.empty())
    throw Error(
        ErrorInfo{.path = "terrain.Terrain/file", .expected = "a .glb or .gltf file", .found = "nothing"});
  auto gpu = std::make_unique<GpuTerrain>();
  LoadedMesh loaded = load_mesh(s, gpu->mesh);
  gpu->positions = upload(loaded.arrays.positions);
  gpu->normals = upload(loaded.arrays.normals);
  gpu->uvs = upload(loaded.arrays.uvs);
  gpu->indices = upload(loaded.arrays.indices);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  gpu->vao = GlVertexArrayName(vao);
  // Positions and uvs as floats, normals packed (pack_normal: 4 bytes, normalized by GL).
  const GLuint buffers[] = {gpu->positions.id(), gpu->normals.id(), gpu->uvs.id()};
  const GLint sizes[] = {3, 4, 2};
  const GLenum types[] = {GL_FLOAT, GL_INT_2_10_10_10_REV, GL_FLOAT};
  const GLsizei strides[] = {sizeof(glm::vec3), sizeof(uint32_t), sizeof(glm::vec2)};
  for (GLuint a = 0; a < 3; ++a) {
    glVertexArrayVertexBuffer(vao, a, buffers[a], 0, strides[a]);
    glVertexArrayAttribFormat(vao, a, sizes[a], types[a], types[a] != GL_FLOAT, 0);
    glVertexArrayAttribBinding(vao, a, a);
    glEnableVertexArrayAttrib(vao, a);
  }
  glVertexArrayElementBuffer(vao, gpu->indices.id());
  // The GPU holds the geometry: only the chunks' bounds and levels stay on the CPU, freed before the
  // images are uploaded so that the two copies never coexist.
  loaded.arrays = {};
  release(loaded.body);
  release(gpu->mesh.positions), release(gpu->mesh.normals);
  release(gpu->mesh.uvs);
  release(gpu->mesh.indices);
  std::shared_ptr<const assets::Model> model = std::move(loaded.model);
  gpu->materials = upload_materials(s, *model);
  // The decoded model leaves the asset cache now that its images are uploaded (a terrain built again
  // with other settings reads the file again).
  model.reset();
  assets.evict_unused();
  assets_without_geometry.evict_unused();
  assets_bare.evict_unused();
  slot = std::move(gpu);
  return *slot;
}

std::vector<GpuMaterial> TerrainCache::upload_materials(const Terrain& s, const assets::Model& model) {
  const bool compress = s.compress_images && bc1_supported();
  const DiskCache disk = compress ? DiskCache::from_environment() : DiskCache();
  // Decoded on the first image whose compressed levels are not on disk, when `model` has no pixels.
  std::shared_ptr<const assets::Model> decoded;
  auto pixels = [&](int image) -> const assets::Image& {
    const assets::Image& img = model.images[size_t(image)];
    if (!img.rgba.empty()) return img;
    if (!decoded) decoded = assets_without_geometry.load(s.file);
    if (size_t(image) >= decoded->images.size() ||
        decoded->images[size_t(image)].encoded_hash != img.encoded_hash)
      throw Error(ErrorInfo{.file = s.file, .path = "/images/" + std::to_string(image),
                            .message = "the file changed while it was being read; load it again"});
    return decoded->images[size_t(image)];
  };
  // Base colour and emissive are sRGB-encoded in glTF; data textures (metallic-roughness, occlusion) linear.
  auto texture = [&](const assets::TextureRef& ref, bool srgb) -> GlTextureName {
    if (!ref.valid() || size_t(ref.texture) >= model.textures.size()) return {};
    const assets::Texture& tex = model.textures[size_t(ref.texture)];
    if (tex.image < 0 || size_t(tex.image) >= model.images.size()) return {};
    if (!compress) return upload_rgba(pixels(tex.image), tex.sampler, srgb);
    const std::string key = bc1_cache_key(model.images[size_t(tex.image)], tex.sampler, srgb);
    std::optional<assets::Bc1Chain> chain;
    if (disk.enabled() && (chain = read_bc1(disk, key))) {
      ++image_cache_reads;
    } else {
      chain = assets::compress_bc1(pixels(tex.image), srgb, assets::mip_edge_of_gl_wrap(tex.sampler.wrap_s),
                                    assets::mip_edge_of_gl_wrap(tex.sampler.wrap_t));
      if (disk.enabled()) write_bc1(disk, key, *chain);
    }
    return upload_bc1(*chain, tex.sampler, srgb);
  };
  std::vector<GpuMaterial> materials;
  for (const assets::Material& mat : model.materials) {
    GpuMaterial g;
    g.base_color_factor = mat.base_color_factor;
    g.metallic = mat.metallic_factor;
    g.roughness = mat.roughness_factor;
    g.emissive = mat.emissive_factor * mat.emissive_strength;
    g.base_color = texture(mat.base_color, true);
    g.metallic_roughness = texture(mat.metallic_roughness, false);
    g.occlusion = texture(mat.occlusion, false);
    g.emissive_map = texture(mat.emissive, true);
    const assets::TextureRef* refs[4] = {&mat.base_color, &mat.metallic_roughness, &mat.occlusion,
                                         &mat.emissive};
    for (size_t i = 0; i < 4; ++i)
      if (refs[i]->transform.present) g.uv_transforms[i] = refs[i]->transform.matrix();
    g.occlusion_strength = mat.occlusion.scale;
    materials.push_back(std::move(g));
  }
  materials.emplace_back();  // primitives without a material: glTF's default (white, rough, dielectric)
  materials.back().metallic = 0.0f;
  return materials;
}

}  // namespace welkin::terrain
