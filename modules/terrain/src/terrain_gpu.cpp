#include "terrain_gpu.h"

#include <algorithm>

#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"

namespace welkin::terrain {

namespace {

GlBufferName upload(std::span<const uint8_t> bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, GLsizeiptr(std::max<size_t>(1, bytes.size())), bytes.empty() ? nullptr : bytes.data(), 0);
  return GlBufferName(id);
}

// `v = {}` assigns an empty list and keeps the capacity: an empty vector swapped in gives it back.
template <class T> void release(std::vector<T>& v) { std::vector<T>().swap(v); }

// Base colour and emissive are sRGB-encoded in glTF; data textures (normal, metallic-roughness) are
// linear. Level 0 only: the levels below are made once the decoded images are freed (make_mipmaps).
GlTextureName upload_image(const assets::Model& model, const assets::TextureRef& ref, bool srgb) {
  if (!ref.valid() || size_t(ref.texture) >= model.textures.size()) return {};
  const assets::Texture& tex = model.textures[size_t(ref.texture)];
  if (tex.image < 0 || size_t(tex.image) >= model.images.size()) return {};
  const assets::Image& img = model.images[size_t(tex.image)];
  if (img.rgba.empty()) return {};
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  int levels = 1 + int(std::floor(std::log2(std::max(img.width, img.height))));
  glTextureStorage2D(id, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height);
  glTextureSubImage2D(id, 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, tex.sampler.wrap_s);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, tex.sampler.wrap_t);
  // No anisotropic filtering: on llvmpipe it multiplies the cost of every terrain pixel several times.
  return GlTextureName(id);
}

std::string cache_key(const Terrain& s) {
  return s.file + "|" + std::to_string(s.chunks_per_side) + "|" + std::to_string(s.lod_levels) + "|" +
         std::to_string(s.refine) + "|" + std::to_string(s.refine_levels) + "|" + std::to_string(s.refine_max_triangles);
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
  loaded.model = assets_without_geometry.load(s.file);
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
  if (cached && std::all_of(cached->chunks.begin(), cached->chunks.end(), [&](const Chunk& c) { return c.material < int(materials); })) {
    mesh = std::move(*cached);
    ++mesh_cache_reads;
    return loaded;
  }
  // A miss: the whole file read again, and the mesh, its materials and its key all taken from that one
  // read (the file may have changed since the first).
  release(loaded.body);
  loaded.model.reset();
  assets_without_geometry.evict_unused();
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
  if (s.file.empty()) throw Error(ErrorInfo{.path = "terrain.Terrain/file", .expected = "a .glb or .gltf file", .found = "nothing"});
  auto gpu = std::make_unique<GpuTerrain>();
  LoadedMesh loaded = load_mesh(s, gpu->mesh);
  gpu->positions = upload(loaded.arrays.positions);
  gpu->normals = upload(loaded.arrays.normals);
  gpu->uvs = upload(loaded.arrays.uvs);
  gpu->indices = upload(loaded.arrays.indices);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  gpu->vao = GlVertexArrayName(vao);
  const GLuint buffers[] = {gpu->positions.id(), gpu->normals.id(), gpu->uvs.id()};
  const GLint sizes[] = {3, 3, 2};
  const GLsizei strides[] = {sizeof(glm::vec3), sizeof(glm::vec3), sizeof(glm::vec2)};
  for (GLuint a = 0; a < 3; ++a) {
    glVertexArrayVertexBuffer(vao, a, buffers[a], 0, strides[a]);
    glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, 0);
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
  for (const assets::Material& mat : model->materials) {
    GpuMaterial g;
    g.base_color_factor = mat.base_color_factor;
    g.metallic = mat.metallic_factor;
    g.roughness = mat.roughness_factor;
    g.emissive = mat.emissive_factor * mat.emissive_strength;
    g.base_color = upload_image(*model, mat.base_color, true);
    g.metallic_roughness = upload_image(*model, mat.metallic_roughness, false);
    g.occlusion = upload_image(*model, mat.occlusion, false);
    g.emissive_map = upload_image(*model, mat.emissive, true);
    if (mat.base_color.transform.present) g.uv_transform = mat.base_color.transform.matrix();
    gpu->materials.push_back(std::move(g));
  }
  gpu->materials.emplace_back();  // primitives without a material: glTF's default (white, rough, dielectric)
  gpu->materials.back().metallic = 0.0f;
  // The decoded model leaves the asset cache now that its images are uploaded (a terrain built again
  // with other settings reads the file again), before the images' levels are made: the decoded
  // images and the levels never coexist.
  model.reset();
  assets.evict_unused();
  assets_without_geometry.evict_unused();
  for (const GpuMaterial& m : gpu->materials)
    for (const GlTextureName* t : {&m.base_color, &m.metallic_roughness, &m.occlusion, &m.emissive_map})
      if (*t) glGenerateTextureMipmap(t->id());
  slot = std::move(gpu);
  return *slot;
}

}  // namespace welkin::terrain
