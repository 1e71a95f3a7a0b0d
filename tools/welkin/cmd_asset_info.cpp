// `welkin info FILE.glb|FILE.gltf`: what a glTF asset contains, as the engine's loader sees it.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "welkin/assets/gltf_loader.h"
#include "welkin/core/error.h"

namespace welkin::cli {

namespace {

using nlohmann::json;

json vec3(const glm::vec3& v) {
  return json::array({v.x, v.y, v.z});
}

json texture_json(const assets::Model& m, const assets::TextureRef& r) {
  if (!r.valid()) return nullptr;
  json t = {{"texture", r.texture}, {"tex_coord", r.tex_coord}};
  const int image = m.textures.at(size_t(r.texture)).image;
  t["image"] = image;
  if (image >= 0) t["size"] = {m.images.at(size_t(image)).width, m.images.at(size_t(image)).height};
  if (r.transform.present)
    t["transform"] = {{"offset", {r.transform.offset.x, r.transform.offset.y}},
                      {"rotation", r.transform.rotation},
                      {"scale", {r.transform.scale.x, r.transform.scale.y}}};
  return t;
}

json describe(const assets::Model& m) {
  json j;
  j["file"] = m.file;
  j["vertices"] = m.vertex_count();
  j["triangles"] = m.triangle_count();
  j["extensions_used"] = m.extensions_used;
  j["extensions_required"] = m.extensions_required;
  j["bounds"] = m.bounds.empty() ? json(nullptr)
                                 : json{{"min", vec3(m.bounds.min)},
                                        {"max", vec3(m.bounds.max)},
                                        {"size", vec3(m.bounds.max - m.bounds.min)}};
  j["scene_roots"] = m.scene_roots;
  j["nodes"] = json::array();
  for (const auto& n : m.nodes)
    j["nodes"].push_back({{"name", n.name},
                          {"mesh", n.mesh},
                          {"parent", n.parent},
                          {"children", n.children},
                          {"translation", vec3(glm::vec3(n.world[3]))}});
  j["meshes"] = json::array();
  for (const auto& mesh : m.meshes) {
    json prims = json::array();
    size_t v = 0, t = 0;
    for (const auto& p : mesh.primitives) {
      prims.push_back({{"vertices", p.positions.size()},
                       {"triangles", p.triangle_count()},
                       {"material", p.material},
                       {"draco", p.draco},
                       {"normals", p.normals_generated ? "generated" : "file"},
                       {"tangents", !p.tangents.empty()},
                       {"uv0", !p.uv0.empty()}});
      v += p.positions.size(), t += p.triangle_count();
    }
    j["meshes"].push_back({{"name", mesh.name}, {"vertices", v}, {"triangles", t}, {"primitives", prims}});
  }
  j["materials"] = json::array();
  for (const auto& mat : m.materials)
    j["materials"].push_back({{"name", mat.name},
                              {"base_color_factor",
                               {mat.base_color_factor.r, mat.base_color_factor.g, mat.base_color_factor.b,
                                mat.base_color_factor.a}},
                              {"metallic", mat.metallic_factor},
                              {"roughness", mat.roughness_factor},
                              {"emissive", vec3(mat.emissive_factor * mat.emissive_strength)},
                              {"alpha_mode", mat.alpha_mode == assets::AlphaMode::opaque ? "OPAQUE"
                                             : mat.alpha_mode == assets::AlphaMode::mask ? "MASK"
                                                                                         : "BLEND"},
                              {"double_sided", mat.double_sided},
                              {"base_color_texture", texture_json(m, mat.base_color)},
                              {"metallic_roughness_texture", texture_json(m, mat.metallic_roughness)},
                              {"normal_texture", texture_json(m, mat.normal)},
                              {"occlusion_texture", texture_json(m, mat.occlusion)},
                              {"emissive_texture", texture_json(m, mat.emissive)}});
  j["images"] = json::array();
  for (const auto& im : m.images)
    j["images"].push_back(
        {{"name", im.name}, {"mime_type", im.mime_type}, {"width", im.width}, {"height", im.height}});
  j["warnings"] = m.warnings;
  return j;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

}  // namespace

void print_asset_info(const std::string& file, bool as_json) {
  const assets::Model m = assets::load_gltf(file);
  const json j = describe(m);
  if (as_json) {
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("%s: glTF 2.0, %zu nodes, %zu meshes, %zu materials, %zu images\n", file.c_str(),
              m.nodes.size(), m.meshes.size(), m.materials.size(), m.images.size());
  std::printf("  %zu vertices, %zu triangles\n", m.vertex_count(), m.triangle_count());
  std::printf("  extensions used: %s; required: %s\n", join(m.extensions_used).c_str(),
              join(m.extensions_required).c_str());
  if (!m.bounds.empty()) {
    const glm::vec3 s = m.bounds.max - m.bounds.min;
    std::printf(
        "  bounds (glTF frame, Y up): min (%.3f, %.3f, %.3f) max (%.3f, %.3f, %.3f) size (%.3f, %.3f, "
        "%.3f)\n",
        m.bounds.min.x, m.bounds.min.y, m.bounds.min.z, m.bounds.max.x, m.bounds.max.y, m.bounds.max.z, s.x,
        s.y, s.z);
  }
  std::printf("\nnodes:\n");
  std::vector<std::pair<int, int>>
      stack;  // (node, depth), iterative: depth is bounded by the node count only
  for (auto it = m.scene_roots.rbegin(); it != m.scene_roots.rend(); ++it) stack.emplace_back(*it, 0);
  while (!stack.empty()) {
    const auto [k, depth] = stack.back();
    stack.pop_back();
    const auto& n = m.nodes.at(size_t(k));
    std::printf("  %*s%d %s%s\n", 2 * std::min(depth, 40), "", k,
                n.name.empty() ? "(unnamed)" : n.name.c_str(),
                n.mesh >= 0 ? (" -> mesh " + std::to_string(n.mesh)).c_str() : "");
    for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.emplace_back(*it, depth + 1);
  }
  std::printf("\nmeshes:\n");
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const auto& mj = j["meshes"][i];
    std::printf("  %zu %s: %zu primitive(s), %zu vertices, %zu triangles\n", i, m.meshes[i].name.c_str(),
                m.meshes[i].primitives.size(), mj["vertices"].get<size_t>(), mj["triangles"].get<size_t>());
    for (const auto& p : m.meshes[i].primitives)
      std::printf("      %zu vertices, %zu triangles, material %d%s%s%s\n", p.positions.size(),
                  p.triangle_count(), p.material, p.draco ? ", Draco" : "", p.uv0.empty() ? "" : ", UV0",
                  p.normals_generated ? ", normals generated" : ", normals");
  }
  std::printf("\nmaterials:\n");
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const auto& mat = m.materials[i];
    std::printf("  %zu %s: base colour (%.3g, %.3g, %.3g, %.3g), metallic %.3g, roughness %.3g", i,
                mat.name.c_str(), mat.base_color_factor.r, mat.base_color_factor.g, mat.base_color_factor.b,
                mat.base_color_factor.a, mat.metallic_factor, mat.roughness_factor);
    for (const auto& [label, ref] : {std::pair{"base colour", &mat.base_color},
                                     {"metal/rough", &mat.metallic_roughness},
                                     {"normal", &mat.normal},
                                     {"occlusion", &mat.occlusion},
                                     {"emissive", &mat.emissive}}) {
      if (!ref->valid()) continue;
      const int image = m.textures.at(size_t(ref->texture)).image;
      std::printf("; %s texture %d", label, ref->texture);
      if (image >= 0)
        std::printf(" (%dx%d)", m.images.at(size_t(image)).width, m.images.at(size_t(image)).height);
      if (ref->transform.present) std::printf(" transformed");
    }
    std::printf("\n");
  }
  if (!m.images.empty()) {
    std::printf("\nimages:\n");
    for (size_t i = 0; i < m.images.size(); ++i)
      std::printf("  %zu %s: %s %dx%d\n", i, m.images[i].name.c_str(), m.images[i].mime_type.c_str(),
                  m.images[i].width, m.images[i].height);
  }
  if (!m.warnings.empty()) {
    std::printf("\nwarnings:\n");
    for (const auto& w : m.warnings) std::printf("  %s\n", w.c_str());
  }
}

}  // namespace welkin::cli
