// tinygltf's model (already validated) to the plain CPU model: attributes dequantized, Draco decoded,
// strips and fans turned into lists, images decoded, node transforms resolved.
#include <cmath>
#include <cstring>
#include <deque>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "internal.h"
#include "tinygltf_config.h"

namespace welkin::assets::detail {

namespace {

using nlohmann::json;

float read_component(const uint8_t* p, int ct, bool normalized) {
  switch (ct) {
    case 5120: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0f, -1.0f) : float(v);
    }
    case 5121:
      return normalized ? *p / 255.0f : float(*p);
    case 5122: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
    }
    case 5123: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : float(v);
    }
    case 5125: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

class Converter {
 public:
  Converter(const tinygltf::Model& gm, const json& doc, const Source& src) : gm_(gm), doc_(doc), src_(src) {}

  Model run() {
    m_.extensions_used = gm_.extensionsUsed;
    m_.extensions_required = gm_.extensionsRequired;
    images();
    for (const auto& t : gm_.textures) {
      Texture tex;
      tex.name = t.name;
      tex.image = t.source;
      if (t.sampler >= 0) {
        const auto& s = gm_.samplers.at(size_t(t.sampler));
        tex.sampler = Sampler{.mag_filter = std::max(s.magFilter, 0),
                              .min_filter = std::max(s.minFilter, 0),
                              .wrap_s = s.wrapS,
                              .wrap_t = s.wrapT};
      }
      m_.textures.push_back(std::move(tex));
    }
    materials();
    meshes();
    nodes();
    return std::move(m_);
  }

 private:
  std::span<const uint8_t> view_bytes(int view, const std::string& path) {
    const auto& v = gm_.bufferViews.at(size_t(view));
    const auto& b = gm_.buffers.at(size_t(v.buffer));
    if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
      fail(src_, path, "a bufferView inside its buffer",
           "bufferView " + std::to_string(view) + " past the buffer's end");
    return std::span<const uint8_t>(b.data.data() + v.byteOffset, v.byteLength);
  }

  // Accessor elements as floats, normalized as the accessor says.
  std::vector<float> read_floats(int index, int comps, const std::string& path) {
    const auto& a = gm_.accessors.at(size_t(index));
    const int csize = component_size(a.componentType);
    const auto bytes = view_bytes(a.bufferView, path);
    const size_t esize = size_t(csize) * comps;
    const size_t stride = gm_.bufferViews[size_t(a.bufferView)].byteStride
                              ? gm_.bufferViews[size_t(a.bufferView)].byteStride
                              : esize;
    if (a.count == 0 || a.byteOffset + stride * (a.count - 1) + esize > bytes.size())
      fail(src_, path, "an accessor inside its bufferView",
           "accessor " + std::to_string(index) + " past its end");
    std::vector<float> out(a.count * comps);
    for (size_t i = 0; i < a.count; ++i) {
      const uint8_t* e = bytes.data() + a.byteOffset + i * stride;
      for (int c = 0; c < comps; ++c) {
        const float v = read_component(e + size_t(c) * csize, a.componentType, a.normalized);
        if (!std::isfinite(v))
          fail(src_, path, "finite numbers",
               "a NaN or infinity in element " + std::to_string(i) + " of accessor " + std::to_string(index));
        out[i * comps + c] = v;
      }
    }
    return out;
  }

  std::vector<uint32_t> read_indices(int index, const std::string& path) {
    const auto& a = gm_.accessors.at(size_t(index));
    const int csize = component_size(a.componentType);
    const auto bytes = view_bytes(a.bufferView, path);
    const size_t stride = gm_.bufferViews[size_t(a.bufferView)].byteStride
                              ? gm_.bufferViews[size_t(a.bufferView)].byteStride
                              : size_t(csize);
    if (a.count == 0 || a.byteOffset + stride * (a.count - 1) + csize > bytes.size())
      fail(src_, path, "an accessor inside its bufferView",
           "accessor " + std::to_string(index) + " past its end");
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
      const uint8_t* e = bytes.data() + a.byteOffset + i * stride;
      if (csize == 1) {
        out[i] = *e;
      } else if (csize == 2) {
        uint16_t v;
        std::memcpy(&v, e, 2);
        out[i] = v;
      } else {
        std::memcpy(&out[i], e, 4);
      }
    }
    return out;
  }

  void images() {
    uint64_t total = 0;
    for (size_t i = 0; i < gm_.images.size(); ++i) {
      const auto& gi = gm_.images[i];
      const std::string path = "/images/" + std::to_string(i);
      Image img;
      img.name = gi.name;
      img.mime_type = gi.mimeType;
      // The encoded bytes are read (and hashed) whether or not they are decoded: the hash names what
      // is derived from them in caches, and a missing external image is an error either way.
      std::vector<uint8_t> external;
      std::span<const uint8_t> encoded;
      std::string where;
      if (gi.bufferView >= 0) {
        where = path + "/bufferView";
        encoded = view_bytes(gi.bufferView, where);
      } else if (gi.bits == 0 && !gi.image.empty()) {
        where = path + "/uri";
        encoded = gi.image;
      } else {
        where = path + "/uri";
        external = read_file_limited(src_, resolve_external(src_, gi.uri, where),
                                     src_.options.limits.max_file_bytes, where);
        encoded = external;
      }
      if (src_.options.decode_images) img = decode_image(encoded, src_, where, total);
      img.name = gi.name;
      img.mime_type = gi.mimeType;
      img.encoded_hash = DiskCache::hash({reinterpret_cast<const char*>(encoded.data()), encoded.size()});
      m_.images.push_back(std::move(img));
    }
  }

  TextureRef texture_ref(int index, int tex_coord, double scale, const json* info, const std::string& path,
                         const std::string& material) {
    TextureRef r;
    if (index < 0) return r;
    r.texture = index;
    r.tex_coord = tex_coord;
    r.scale = float(scale);
    if (info && info->contains("extensions") && (*info)["extensions"].contains("KHR_texture_transform")) {
      const json& t = (*info)["extensions"]["KHR_texture_transform"];
      r.transform.present = true;
      if (t.contains("offset"))
        r.transform.offset = {t["offset"][0].get<float>(), t["offset"][1].get<float>()};
      if (t.contains("scale")) r.transform.scale = {t["scale"][0].get<float>(), t["scale"][1].get<float>()};
      r.transform.rotation = t.value("rotation", 0.0f);
      if (t.contains("texCoord")) r.tex_coord = t["texCoord"].get<int>();
    }
    if (r.tex_coord != 0)
      m_.warnings.push_back(material + path + " reads TEXCOORD_" + std::to_string(r.tex_coord) +
                            ", which is not loaded (only TEXCOORD_0 is)");
    return r;
  }

  void materials() {
    for (size_t i = 0; i < gm_.materials.size(); ++i) {
      const auto& g = gm_.materials[i];
      const json& jm = doc_["materials"][i];
      const json* pbr = jm.contains("pbrMetallicRoughness") ? &jm["pbrMetallicRoughness"] : nullptr;
      auto info = [](const json* parent, const char* key) -> const json* {
        return parent && parent->contains(key) ? &(*parent)[key] : nullptr;
      };
      const std::string mp = "/materials/" + std::to_string(i);
      Material m;
      m.name = g.name;
      const auto& f = g.pbrMetallicRoughness.baseColorFactor;
      if (f.size() == 4) m.base_color_factor = glm::vec4(f[0], f[1], f[2], f[3]);
      m.metallic_factor = float(g.pbrMetallicRoughness.metallicFactor);
      m.roughness_factor = float(g.pbrMetallicRoughness.roughnessFactor);
      if (g.emissiveFactor.size() == 3)
        m.emissive_factor = glm::vec3(g.emissiveFactor[0], g.emissiveFactor[1], g.emissiveFactor[2]);
      if (jm.contains("extensions") && jm["extensions"].contains("KHR_materials_emissive_strength"))
        m.emissive_strength =
            jm["extensions"]["KHR_materials_emissive_strength"].value("emissiveStrength", 1.0f);
      const auto& bct = g.pbrMetallicRoughness.baseColorTexture;
      const auto& mrt = g.pbrMetallicRoughness.metallicRoughnessTexture;
      m.base_color = texture_ref(bct.index, bct.texCoord, 1.0, info(pbr, "baseColorTexture"),
                                 "/pbrMetallicRoughness/baseColorTexture", mp);
      m.metallic_roughness = texture_ref(mrt.index, mrt.texCoord, 1.0, info(pbr, "metallicRoughnessTexture"),
                                         "/pbrMetallicRoughness/metallicRoughnessTexture", mp);
      m.normal = texture_ref(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.scale,
                             info(&jm, "normalTexture"), "/normalTexture", mp);
      m.occlusion =
          texture_ref(g.occlusionTexture.index, g.occlusionTexture.texCoord, g.occlusionTexture.strength,
                      info(&jm, "occlusionTexture"), "/occlusionTexture", mp);
      m.emissive = texture_ref(g.emissiveTexture.index, g.emissiveTexture.texCoord, 1.0,
                               info(&jm, "emissiveTexture"), "/emissiveTexture", mp);
      m.alpha_mode = g.alphaMode == "MASK"    ? AlphaMode::mask
                     : g.alphaMode == "BLEND" ? AlphaMode::blend
                                              : AlphaMode::opaque;
      m.alpha_cutoff = float(g.alphaCutoff);
      m.double_sided = g.doubleSided;
      m_.materials.push_back(std::move(m));
    }
  }

  void meshes() {
    for (size_t i = 0; i < gm_.meshes.size(); ++i) {
      Mesh mesh;
      mesh.name = gm_.meshes[i].name;
      for (size_t j = 0; src_.options.decode_meshes && j < gm_.meshes[i].primitives.size(); ++j) {
        const std::string pp = "/meshes/" + std::to_string(i) + "/primitives/" + std::to_string(j);
        Primitive p;
        if (primitive(gm_.meshes[i].primitives[j], doc_["meshes"][i]["primitives"][j], pp, p))
          mesh.primitives.push_back(std::move(p));
      }
      m_.meshes.push_back(std::move(mesh));
    }
  }

  bool primitive(const tinygltf::Primitive& gp, const json& jp, const std::string& pp, Primitive& p) {
    const int mode = gp.mode < 0 ? 4 : gp.mode;
    if (mode < 4) {
      m_.warnings.push_back(pp + ": skipped (mode " + std::to_string(mode) + " is points or lines)");
      return false;
    }
    auto pos_it = gp.attributes.find("POSITION");
    if (pos_it == gp.attributes.end()) {
      m_.warnings.push_back(pp + ": skipped (no POSITION)");
      return false;
    }
    p.material = gp.material;
    const json* draco = nullptr;
    if (jp.contains("extensions") && jp["extensions"].contains("KHR_draco_mesh_compression"))
      draco = &jp["extensions"]["KHR_draco_mesh_compression"];
    // The attributes a primitive is built from, and their component counts.
    static constexpr std::pair<const char*, int> kAttributes[] = {
        {"POSITION", 3}, {"NORMAL", 3}, {"TANGENT", 4}, {"TEXCOORD_0", 2}};
    DracoMesh decoded;
    const std::string dp = pp + "/extensions/KHR_draco_mesh_compression";
    if (draco) {
      p.draco = true;
      DracoExpected expected;
      expected.points = gm_.accessors.at(size_t(pos_it->second)).count;  // all attributes agree (validated)
      if (const int ia = jp.value("indices", -1); ia >= 0)
        expected.indices = int64_t(gm_.accessors.at(size_t(ia)).count);
      for (const auto& [name, comps] : kAttributes) {
        const auto it = gp.attributes.find(name);
        if (it == gp.attributes.end() || !(*draco)["attributes"].contains(name)) continue;
        const auto& a = gm_.accessors.at(size_t(it->second));
        expected.attributes.push_back({.name = name,
                                       .unique_id = (*draco)["attributes"][name].get<int>(),
                                       .components = comps,
                                       .component_type = a.componentType,
                                       .normalized = a.normalized,
                                       .path = dp + "/attributes/" + name});
      }
      decoded =
          decode_draco(view_bytes((*draco)["bufferView"].get<int>(), dp + "/bufferView"), expected, src_, dp);
      // Every attribute, used here or not, must have exactly the accessor's count of decoded points.
      for (const auto& [name, accessor] : gp.attributes) {
        const auto& a = gm_.accessors.at(size_t(accessor));
        if (a.count != decoded.num_points)
          fail(src_, pp + "/attributes/" + pointer_key(name),
               std::to_string(a.count) + " vertices (accessor " + std::to_string(accessor) + " count)",
               std::to_string(decoded.num_points) + " decoded by Draco");
      }
    }
    // Reads one attribute from the Draco stream when compressed there, else from its accessor.
    auto attribute = [&](const char* name, int comps) -> std::vector<float> {
      auto it = gp.attributes.find(name);
      if (it == gp.attributes.end()) return {};
      if (auto d = decoded.attributes.find(name); d != decoded.attributes.end())
        return std::move(d->second.values);
      return read_floats(it->second, comps, pp + "/attributes/" + name);
    };
    const std::vector<float> pos = attribute("POSITION", 3);
    const size_t n = pos.size() / 3;
    p.positions.resize(n);
    std::memcpy(p.positions.data(), pos.data(), pos.size() * sizeof(float));
    if (auto v = attribute("NORMAL", 3); !v.empty()) {
      p.normals.resize(n);
      std::memcpy(p.normals.data(), v.data(), v.size() * sizeof(float));
    }
    if (auto v = attribute("TANGENT", 4); !v.empty()) {
      p.tangents.resize(n);
      std::memcpy(p.tangents.data(), v.data(), v.size() * sizeof(float));
    }
    if (auto v = attribute("TEXCOORD_0", 2); !v.empty()) {
      p.uv0.resize(n);
      std::memcpy(p.uv0.data(), v.data(), v.size() * sizeof(float));
    }
    std::vector<uint32_t> idx;
    const std::string ip = pp + "/indices";
    const int indices = jp.value("indices", -1);  // tinygltf was given Draco primitives without it
    if (draco) {
      idx = std::move(decoded.indices);
      if (indices >= 0 && gm_.accessors.at(size_t(indices)).count != idx.size())
        fail(src_, ip,
             std::to_string(gm_.accessors[size_t(indices)].count) + " indices (accessor " +
                 std::to_string(indices) + " count)",
             std::to_string(idx.size()) + " decoded by Draco");
    } else if (indices >= 0) {
      idx = read_indices(indices, ip);
    } else {
      idx.resize(n);
      for (size_t k = 0; k < n; ++k) idx[k] = uint32_t(k);
    }
    for (size_t k = 0; k < idx.size(); ++k)
      if (idx[k] >= n)
        fail(src_, ip, "indices below the vertex count " + std::to_string(n),
             "index " + std::to_string(idx[k]) + " at element " + std::to_string(k));
    if (mode == 4) {
      if (idx.size() % 3 != 0)
        fail(src_, indices >= 0 ? ip : pp + "/attributes/POSITION", "a multiple of 3 indices for TRIANGLES",
             std::to_string(idx.size()));
      p.indices = std::move(idx);
    } else {
      for (size_t k = 2; k < idx.size(); ++k) {
        const uint32_t a = mode == 6 ? idx[0] : idx[k - 2];
        const uint32_t b = mode == 5 && (k % 2) ? idx[k] : idx[k - 1];
        const uint32_t c = mode == 5 && (k % 2) ? idx[k - 1] : idx[k];
        p.indices.insert(p.indices.end(), {a, b, c});
      }
    }
    for (const glm::vec3& v : p.positions) p.bounds.extend(v);
    if (p.normals.empty()) generate_normals(p);
    return true;
  }

  static void generate_normals(Primitive& p) {
    p.normals_generated = true;
    p.normals.assign(p.positions.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
      const uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
      const glm::vec3 n = glm::cross(p.positions[b] - p.positions[a], p.positions[c] - p.positions[a]);
      p.normals[a] += n, p.normals[b] += n, p.normals[c] += n;
    }
    for (glm::vec3& n : p.normals) {
      const float len = glm::length(n);
      n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
  }

  void nodes() {
    const size_t count = gm_.nodes.size();
    m_.nodes.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const auto& g = gm_.nodes[i];
      Node& n = m_.nodes[i];
      n.name = g.name;
      n.mesh = g.mesh;
      n.children = g.children;
      if (g.matrix.size() == 16) {
        double d[16];
        std::copy(g.matrix.begin(), g.matrix.end(), d);
        n.local = glm::mat4(glm::make_mat4(d));
      } else {
        if (g.translation.size() == 3)
          n.translation = glm::vec3(g.translation[0], g.translation[1], g.translation[2]);
        if (g.rotation.size() == 4)
          n.rotation = glm::quat(float(g.rotation[3]), float(g.rotation[0]), float(g.rotation[1]),
                                 float(g.rotation[2]));
        if (g.scale.size() == 3) n.scale = glm::vec3(g.scale[0], g.scale[1], g.scale[2]);
        n.local = glm::translate(glm::mat4(1.0f), n.translation) *
                  glm::mat4_cast(glm::normalize(n.rotation)) * glm::scale(glm::mat4(1.0f), n.scale);
      }
    }
    for (size_t i = 0; i < count; ++i)
      for (int c : m_.nodes[i].children) m_.nodes.at(size_t(c)).parent = int(i);
    std::deque<int> queue;
    for (size_t i = 0; i < count; ++i)
      if (m_.nodes[i].parent < 0) {
        m_.nodes[i].world = m_.nodes[i].local;
        queue.push_back(int(i));
      }
    while (!queue.empty()) {  // iterative: hierarchy depth is bounded only by the node count
      const int k = queue.front();
      queue.pop_front();
      for (int c : m_.nodes[size_t(k)].children) {
        m_.nodes[size_t(c)].world = m_.nodes[size_t(k)].world * m_.nodes[size_t(c)].local;
        queue.push_back(c);
      }
    }
    int scene = gm_.defaultScene >= 0 ? gm_.defaultScene : (gm_.scenes.empty() ? -1 : 0);
    if (scene >= 0 && size_t(scene) < gm_.scenes.size()) {
      m_.scene_roots = gm_.scenes[size_t(scene)].nodes;
    } else {
      for (size_t i = 0; i < count; ++i)
        if (m_.nodes[i].parent < 0) m_.scene_roots.push_back(int(i));
    }
    // Box of every mesh instance reachable from the scene, or of the meshes alone without nodes.
    std::vector<int> stack(m_.scene_roots.begin(), m_.scene_roots.end());
    while (!stack.empty()) {
      const Node& n = m_.nodes.at(size_t(stack.back()));
      stack.pop_back();
      stack.insert(stack.end(), n.children.begin(), n.children.end());
      if (n.mesh < 0) continue;
      for (const Primitive& p : m_.meshes.at(size_t(n.mesh)).primitives) {
        if (p.bounds.empty()) continue;
        for (int c = 0; c < 8; ++c) {
          const glm::vec3 corner((c & 1) ? p.bounds.max.x : p.bounds.min.x,
                                 (c & 2) ? p.bounds.max.y : p.bounds.min.y,
                                 (c & 4) ? p.bounds.max.z : p.bounds.min.z);
          m_.bounds.extend(glm::vec3(n.world * glm::vec4(corner, 1.0f)));
        }
      }
    }
    if (count == 0)
      for (const Mesh& mesh : m_.meshes)
        for (const Primitive& p : mesh.primitives) m_.bounds.extend(p.bounds);
  }

  const tinygltf::Model& gm_;
  const json& doc_;
  const Source& src_;
  Model m_;
};

}  // namespace

Model convert_model(const tinygltf::Model& gm, const nlohmann::json& doc, const Source& src) {
  return Converter(gm, doc, src).run();
}

}  // namespace welkin::assets::detail
