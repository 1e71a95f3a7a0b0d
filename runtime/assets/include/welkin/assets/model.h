#pragma once
// A plain CPU copy of a glTF 2.0 asset: everything decoded (Draco, quantized attributes, images)
// so renderers and tools never touch glTF accessors. Units and axes are glTF's: metres, +Y up.
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <string>
#include <vector>

namespace welkin::assets {

// Axis-aligned box; empty until the first point is added.
struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) {
      extend(b.min);
      extend(b.max);
    }
  }
};

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv, as the extension defines.
struct TextureTransform {
  bool present = false;
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space
  glm::vec2 scale{1.0f};
  glm::mat3 matrix() const;
};

// A material's reference to a texture; `texture < 0` means none.
struct TextureRef {
  int texture = -1;
  int tex_coord = 0;   // which TEXCOORD_n the texture reads (only TEXCOORD_0 is loaded)
  float scale = 1.0f;  // normalTexture.scale or occlusionTexture.strength
  TextureTransform transform;
  bool valid() const { return texture >= 0; }
};

enum class AlphaMode { opaque, mask, blend };

// glTF metallic-roughness PBR material, factors already defaulted as the specification says.
struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  glm::vec3 emissive_factor{0.0f};
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength (multiplies emissive_factor)
  TextureRef base_color, metallic_roughness, normal, occlusion, emissive;
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

// Decoded image, rows top to bottom, 4 bytes per pixel (empty when images were not decoded).
struct Image {
  std::string name;
  std::string mime_type;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  uint64_t encoded_hash = 0;  // DiskCache::hash of its PNG or JPEG bytes, decoded or not
};

// GL enum values as glTF stores them (9729 LINEAR, 10497 REPEAT, ...); 0 = unspecified.
struct Sampler {
  int mag_filter = 0, min_filter = 0;
  int wrap_s = 10497, wrap_t = 10497;
};

struct Texture {
  std::string name;
  int image = -1;
  Sampler sampler;
};

// One triangle list. Attributes are de-indexed from glTF accessors and dequantized to floats.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // always filled; see normals_generated
  std::vector<glm::vec4> tangents;  // empty when the file has none (w = handedness)
  std::vector<glm::vec2> uv0;       // empty when the file has no TEXCOORD_0
  std::vector<uint32_t> indices;    // 3 per triangle, each < positions.size()
  int material = -1;
  Bounds bounds;                   // of positions, in the mesh's own frame
  bool draco = false;              // decoded from KHR_draco_mesh_compression
  bool normals_generated = false;  // the file had no NORMAL; smooth normals were computed
  size_t triangle_count() const { return indices.size() / 3; }
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

struct Node {
  std::string name;
  int mesh = -1;
  int parent = -1;
  std::vector<int> children;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  glm::mat4 local{1.0f};  // from `matrix` or from T * R * S
  glm::mat4 world{1.0f};  // parent chain applied
};

struct Model {
  std::string file;
  std::vector<Node> nodes;
  std::vector<int> scene_roots;  // root nodes of the default scene (all roots when none is named)
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Image> images;
  std::vector<std::string> extensions_used, extensions_required;
  Bounds bounds;                      // world-space box of every mesh instance in the scene
  std::vector<std::string> warnings;  // things skipped on purpose (e.g. line primitives)
  // FNV-1a (DiskCache::hash) chained over the size and bytes of every file the load read, in the order
  // read: the file, its external buffers, and its external images.
  uint64_t content_hash = 0;

  size_t vertex_count() const;
  size_t triangle_count() const;
};

}  // namespace welkin::assets
