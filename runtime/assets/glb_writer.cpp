#include "welkin/assets/glb_writer.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <cstring>

#include "welkin/core/error.h"
#include "welkin/scene/scene_file.h"

namespace welkin::assets {

namespace {

using nlohmann::json;

void put_u32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s += char((v >> (8 * i)) & 0xff);
}

json vec(std::initializer_list<float> v) {
  json a = json::array();
  for (float x : v) a.push_back(x);
  return a;
}

[[noreturn]] void bad(const std::string& path, const std::string& expected, const std::string& found) {
  throw Error(ErrorInfo{.file = "", .path = path, .expected = expected, .found = found});
}

void check_mesh(const MeshData& m) {
  const std::string p = "/meshes/" + m.name;
  if (m.positions.empty()) bad(p + "/positions", "at least one vertex", "none");
  if (!m.normals.empty() && m.normals.size() != m.positions.size())
    bad(p + "/normals", std::to_string(m.positions.size()) + " normals", std::to_string(m.normals.size()));
  if (!m.uv0.empty() && m.uv0.size() != m.positions.size())
    bad(p + "/uv0", std::to_string(m.positions.size()) + " UVs", std::to_string(m.uv0.size()));
  if (m.indices.empty() || m.indices.size() % 3 != 0)
    bad(p + "/indices", "a non-zero multiple of 3", std::to_string(m.indices.size()));
  for (uint32_t i : m.indices)
    if (i >= m.positions.size())
      bad(p + "/indices", "indices below " + std::to_string(m.positions.size()), std::to_string(i));
}

}  // namespace

GlbWriter::GlbWriter() {
  doc_["asset"] = {{"version", "2.0"}, {"generator", "Welkin GlbWriter"}};
  doc_["scene"] = 0;
  doc_["scenes"] = json::array({json{{"nodes", json::array()}}});
}

void GlbWriter::use_extension(const std::string& name, bool required) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (std::string(key) == "extensionsRequired" && !required) continue;
    json& list = doc_[key];
    if (!list.is_array()) list = json::array();
    if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
  }
}

int GlbWriter::add_view(const void* data, size_t bytes, int target) {
  while (bin_.size() % 4) bin_.push_back(0);
  json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
  if (target) v["target"] = target;
  const auto* p = static_cast<const uint8_t*>(data);
  bin_.insert(bin_.end(), p, p + bytes);
  doc_["bufferViews"].push_back(v);
  return int(doc_["bufferViews"].size()) - 1;
}

int GlbWriter::add_image(const std::vector<uint8_t>& encoded, const std::string& mime_type,
                         const std::string& name) {
  json im = {{"bufferView", add_view(encoded.data(), encoded.size(), 0)}, {"mimeType", mime_type}};
  if (!name.empty()) im["name"] = name;
  doc_["images"].push_back(im);
  return int(doc_["images"].size()) - 1;
}

int GlbWriter::add_texture(int image, const Sampler& s) {
  json smp = {{"wrapS", s.wrap_s}, {"wrapT", s.wrap_t}};
  if (s.mag_filter) smp["magFilter"] = s.mag_filter;
  if (s.min_filter) smp["minFilter"] = s.min_filter;
  doc_["samplers"].push_back(smp);
  doc_["textures"].push_back({{"source", image}, {"sampler", int(doc_["samplers"].size()) - 1}});
  return int(doc_["textures"].size()) - 1;
}

int GlbWriter::add_material(const Material& m) {
  auto tex = [&](const TextureRef& r) {
    json t = {{"index", r.texture}};
    if (r.tex_coord) t["texCoord"] = r.tex_coord;
    if (r.transform.present) {
      use_extension("KHR_texture_transform", false);
      t["extensions"]["KHR_texture_transform"] = {
          {"offset", vec({r.transform.offset.x, r.transform.offset.y})},
          {"rotation", r.transform.rotation},
          {"scale", vec({r.transform.scale.x, r.transform.scale.y})}};
    }
    return t;
  };
  json j;
  if (!m.name.empty()) j["name"] = m.name;
  json pbr = {{"baseColorFactor", vec({m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b,
                                       m.base_color_factor.a})},
              {"metallicFactor", m.metallic_factor},
              {"roughnessFactor", m.roughness_factor}};
  if (m.base_color.valid()) pbr["baseColorTexture"] = tex(m.base_color);
  if (m.metallic_roughness.valid()) pbr["metallicRoughnessTexture"] = tex(m.metallic_roughness);
  j["pbrMetallicRoughness"] = pbr;
  if (m.normal.valid()) (j["normalTexture"] = tex(m.normal))["scale"] = m.normal.scale;
  if (m.occlusion.valid()) (j["occlusionTexture"] = tex(m.occlusion))["strength"] = m.occlusion.scale;
  if (m.emissive.valid()) j["emissiveTexture"] = tex(m.emissive);
  if (m.emissive_factor != glm::vec3(0.0f))
    j["emissiveFactor"] = vec({m.emissive_factor.r, m.emissive_factor.g, m.emissive_factor.b});
  if (m.emissive_strength != 1.0f) {
    use_extension("KHR_materials_emissive_strength", false);
    j["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", m.emissive_strength}};
  }
  if (m.alpha_mode != AlphaMode::opaque) j["alphaMode"] = m.alpha_mode == AlphaMode::mask ? "MASK" : "BLEND";
  if (m.alpha_mode == AlphaMode::mask) j["alphaCutoff"] = m.alpha_cutoff;
  if (m.double_sided) j["doubleSided"] = true;
  doc_["materials"].push_back(j);
  return int(doc_["materials"].size()) - 1;
}

WrittenMesh GlbWriter::add_mesh(const MeshData& m, const DracoSettings& ds) {
  check_mesh(m);
  json& accessors = doc_["accessors"];
  if (!accessors.is_array()) accessors = json::array();
  auto add_accessor = [&](int view, int ctype, const char* type, size_t count) {
    json a = {{"componentType", ctype}, {"type", type}, {"count", count}};
    if (view >= 0) a["bufferView"] = view;
    accessors.push_back(a);
    return int(accessors.size()) - 1;
  };
  auto minmax = [](const std::vector<glm::vec3>& p, json& a) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
    a["min"] = vec({lo.x, lo.y, lo.z});
    a["max"] = vec({hi.x, hi.y, hi.z});
  };
  json prim;
  WrittenMesh out;
  const size_t bin_before = bin_.size();
  if (!ds.enabled) {
    prim["attributes"]["POSITION"] = add_accessor(
        add_view(m.positions.data(), m.positions.size() * 12, 34962), 5126, "VEC3", m.positions.size());
    minmax(m.positions, accessors.back());
    if (!m.normals.empty())
      prim["attributes"]["NORMAL"] = add_accessor(add_view(m.normals.data(), m.normals.size() * 12, 34962),
                                                  5126, "VEC3", m.normals.size());
    if (!m.uv0.empty())
      prim["attributes"]["TEXCOORD_0"] =
          add_accessor(add_view(m.uv0.data(), m.uv0.size() * 8, 34962), 5126, "VEC2", m.uv0.size());
    prim["indices"] = add_accessor(add_view(m.indices.data(), m.indices.size() * 4, 34963), 5125, "SCALAR",
                                   m.indices.size());
    out.vertices = uint32_t(m.positions.size());
    out.triangles = uint32_t(m.indices.size() / 3);
  } else {
    draco::Mesh dm;
    const uint32_t n = uint32_t(m.positions.size());
    dm.set_num_points(n);
    auto attr = [&](draco::GeometryAttribute::Type type, int comps, const float* data) {
      draco::GeometryAttribute ga;
      ga.Init(type, nullptr, uint8_t(comps), draco::DT_FLOAT32, false, int64_t(sizeof(float)) * comps, 0);
      const int id = dm.AddAttribute(ga, true, n);
      for (uint32_t i = 0; i < n; ++i)
        dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), data + size_t(i) * comps);
      return int(dm.attribute(id)->unique_id());
    };
    json dattrs;
    dattrs["POSITION"] = attr(draco::GeometryAttribute::POSITION, 3, &m.positions[0].x);
    if (!m.normals.empty()) dattrs["NORMAL"] = attr(draco::GeometryAttribute::NORMAL, 3, &m.normals[0].x);
    if (!m.uv0.empty()) dattrs["TEXCOORD_0"] = attr(draco::GeometryAttribute::TEX_COORD, 2, &m.uv0[0].x);
    for (size_t t = 0; t < m.indices.size(); t += 3)
      dm.AddFace({draco::PointIndex(m.indices[t]), draco::PointIndex(m.indices[t + 1]),
                  draco::PointIndex(m.indices[t + 2])});
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, ds.position_bits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, ds.normal_bits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, ds.uv_bits);
    enc.SetSpeedOptions(ds.speed, ds.speed);
    enc.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buf;
    const draco::Status st = enc.EncodeMeshToBuffer(dm, &buf);
    if (!st.ok()) bad("/meshes/" + m.name, "a mesh Draco can encode", st.error_msg_string());
    // Accessor counts and POSITION bounds must describe what a decoder gets back, so decode it.
    draco::DecoderBuffer dbuf;
    dbuf.Init(buf.data(), buf.size());
    auto decoded = draco::Decoder().DecodeMeshFromBuffer(&dbuf);
    if (!decoded.ok())
      bad("/meshes/" + m.name, "a Draco stream that decodes", decoded.status().error_msg_string());
    const draco::Mesh& back = *decoded.value();
    out.vertices = back.num_points();
    out.triangles = back.num_faces();
    const int view = add_view(buf.data(), buf.size(), 0);
    prim["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", view}, {"attributes", dattrs}};
    std::vector<glm::vec3> dpos(back.num_points());
    const draco::PointAttribute* pa = back.GetAttributeByUniqueId(dattrs["POSITION"].get<uint32_t>());
    for (draco::PointIndex i(0); i < back.num_points(); ++i)
      pa->ConvertValue<float>(pa->mapped_index(i), 3, &dpos[i.value()].x);
    prim["attributes"]["POSITION"] = add_accessor(-1, 5126, "VEC3", out.vertices);
    minmax(dpos, accessors.back());
    if (!m.normals.empty()) prim["attributes"]["NORMAL"] = add_accessor(-1, 5126, "VEC3", out.vertices);
    if (!m.uv0.empty()) prim["attributes"]["TEXCOORD_0"] = add_accessor(-1, 5126, "VEC2", out.vertices);
    prim["indices"] = add_accessor(-1, 5125, "SCALAR", size_t(out.triangles) * 3);
    use_extension("KHR_draco_mesh_compression", true);
  }
  if (m.material >= 0) prim["material"] = m.material;
  prim["mode"] = 4;
  json mesh = {{"primitives", json::array({prim})}};
  if (!m.name.empty()) mesh["name"] = m.name;
  doc_["meshes"].push_back(mesh);
  out.mesh = int(doc_["meshes"].size()) - 1;
  out.bytes = bin_.size() - bin_before;
  return out;
}

int GlbWriter::add_node(const std::string& name, int mesh, const glm::vec3& t, const glm::quat& r,
                        const glm::vec3& s, int parent) {
  json n;
  if (!name.empty()) n["name"] = name;
  if (mesh >= 0) n["mesh"] = mesh;
  if (t != glm::vec3(0.0f)) n["translation"] = vec({t.x, t.y, t.z});
  if (r != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) n["rotation"] = vec({r.x, r.y, r.z, r.w});
  if (s != glm::vec3(1.0f)) n["scale"] = vec({s.x, s.y, s.z});
  doc_["nodes"].push_back(n);
  const int index = int(doc_["nodes"].size()) - 1;
  if (parent >= 0)
    doc_["nodes"].at(size_t(parent))["children"].push_back(index);
  else
    doc_["scenes"][0]["nodes"].push_back(index);
  return index;
}

std::string GlbWriter::assemble(const json& doc, const std::vector<uint8_t>& bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  const size_t bin_padded = (bin.size() + 3) / 4 * 4;
  std::string out;
  put_u32(out, 0x46546C67);
  put_u32(out, 2);
  put_u32(out, uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin_padded)));
  put_u32(out, uint32_t(text.size()));
  put_u32(out, 0x4E4F534A);
  out += text;
  if (!bin.empty()) {
    put_u32(out, uint32_t(bin_padded));
    put_u32(out, 0x004E4942);
    out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
    out.append(bin_padded - bin.size(), '\0');
  }
  return out;
}

std::string GlbWriter::glb() const {
  json doc = doc_;
  if (!bin_.empty()) doc["buffers"] = json::array({json{{"byteLength", (bin_.size() + 3) / 4 * 4}}});
  return assemble(doc, bin_);
}

void GlbWriter::write(const std::string& path) const {
  write_file_atomically(path, glb());
}

}  // namespace welkin::assets
