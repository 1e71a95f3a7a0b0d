#pragma once
// Writes binary glTF (.glb) with optional KHR_draco_mesh_compression, for asset generators and tests.
// Output is deterministic: the same calls give the same bytes (JSON keys sorted, no timestamps).
#include <cstdint>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "welkin/assets/model.h"

namespace welkin::assets {

struct MeshData {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // optional (empty, or one per position)
  std::vector<glm::vec2> uv0;      // optional
  std::vector<uint32_t> indices;   // triangles
  int material = -1;
};

// Draco quantization bits per attribute; more bits, larger file, smaller error.
struct DracoSettings {
  bool enabled = false;
  int position_bits = 14;
  int normal_bits = 10;
  int uv_bits = 12;
  int speed = 0;  // 0 = best compression ... 10 = fastest
};

// What a mesh turned into (Draco may reorder and split vertices; these are the decoded counts).
struct WrittenMesh {
  int mesh = -1;
  uint32_t vertices = 0;
  uint32_t triangles = 0;
  uint64_t bytes = 0;  // bytes of BIN used by the mesh
};

class GlbWriter {
 public:
  GlbWriter();
  // Embeds an encoded PNG/JPEG; returns the image index.
  int add_image(const std::vector<uint8_t>& encoded, const std::string& mime_type,
                const std::string& name = "");
  int add_texture(int image, const Sampler& sampler = {});
  // Texture references use texture indices from add_texture; KHR_texture_transform when present.
  int add_material(const Material& material);
  // Throws welkin::Error when the mesh is malformed or Draco fails to encode it.
  WrittenMesh add_mesh(const MeshData& mesh, const DracoSettings& draco = {});
  // Adds a node (a root unless `parent` >= 0); returns its index.
  int add_node(const std::string& name, int mesh, const glm::vec3& translation = glm::vec3(0.0f),
               const glm::quat& rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
               const glm::vec3& scale = glm::vec3(1.0f), int parent = -1);

  // Raw access for tests that corrupt a file on purpose, and for extras.
  nlohmann::json& document() { return doc_; }
  std::vector<uint8_t>& bin() { return bin_; }

  // The .glb bytes, or writes them atomically (temporary file, then rename).
  std::string glb() const;
  void write(const std::string& path) const;

  // Assembles any JSON document and BIN chunk into .glb bytes (BIN omitted when empty).
  static std::string assemble(const nlohmann::json& doc, const std::vector<uint8_t>& bin);

 private:
  int add_view(const void* data, size_t bytes, int target);
  void use_extension(const std::string& name, bool required);
  nlohmann::json doc_;
  std::vector<uint8_t> bin_;
};

}  // namespace welkin::assets
