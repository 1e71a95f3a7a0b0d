// The glTF validator's checks of materials, meshes and their primitives, nodes and scenes (the rest
// and the helpers: gltf_validate.cpp, gltf_validator.h).
#include <algorithm>

#include "gltf_validator.h"

namespace welkin::assets::detail {

void Validator::materials() {
  for (size_t i = 0; i < sizes_["materials"]; ++i) {
    const json& m = at("materials", i);
    const std::string p = "/materials/" + std::to_string(i);
    string(m, "name", p, false);
    if (const json* pbr = object(m, "pbrMetallicRoughness", p)) {
      const std::string pp = p + "/pbrMetallicRoughness";
      number_array(*pbr, "baseColorFactor", pp, 4, 0.0, 1.0);
      number(*pbr, "metallicFactor", pp, 1.0, 0.0, 1.0);
      number(*pbr, "roughnessFactor", pp, 1.0, 0.0, 1.0);
      texture_info(*pbr, "baseColorTexture", pp);
      texture_info(*pbr, "metallicRoughnessTexture", pp);
    }
    texture_info(m, "normalTexture", p);
    texture_info(m, "occlusionTexture", p);
    texture_info(m, "emissiveTexture", p);
    number_array(m, "emissiveFactor", p, 3, 0.0, 1.0);
    if (const json* e = object(m, "extensions", p))
      if (const json* es = object(*e, "KHR_materials_emissive_strength", p + "/extensions"))
        number(*es, "emissiveStrength", p + "/extensions/KHR_materials_emissive_strength", 1.0, 0.0,
               HUGE_VAL);
    const std::string mode = string(m, "alphaMode", p, false);
    if (!mode.empty() && mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
      fail(src_, p + "/alphaMode", "\"OPAQUE\", \"MASK\" or \"BLEND\"", "\"" + mode + "\"");
    number(m, "alphaCutoff", p, 0.5, 0.0, HUGE_VAL);
    boolean(m, "doubleSided", p);
  }
}

// Component types an attribute may use: core glTF, widened by KHR_mesh_quantization when declared.
void Validator::attribute_format(const std::string& name, int accessor, const std::string& path) {
  const AccessorInfo& a = accessors_[accessor];
  const bool quant = used_.count("KHR_mesh_quantization") > 0;
  const int ct = a.component_type;
  const bool n = a.normalized;
  auto need = [&](const char* type, bool ok, const char* formats) {
    if (a.type != type)
      fail(src_, path, std::string(type) + " accessor",
           "accessor " + std::to_string(accessor) + " of " + a.type);
    if (!ok)
      fail(src_, path, std::string(formats) + (quant ? "" : " (others need KHR_mesh_quantization)"),
           "accessor " + std::to_string(accessor) + " with componentType " + std::to_string(ct) +
               (n ? " normalized" : ""));
  };
  if (name == "POSITION") {
    need("VEC3", ct == 5126 || (quant && ct != 5125),
         quant ? "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT" : "FLOAT");
  } else if (name == "NORMAL") {
    need("VEC3", ct == 5126 || (quant && (ct == 5120 || ct == 5122) && n),
         quant ? "FLOAT or normalized BYTE/SHORT" : "FLOAT");
  } else if (name == "TANGENT") {
    need("VEC4", ct == 5126 || (quant && (ct == 5120 || ct == 5122) && n),
         quant ? "FLOAT or normalized BYTE/SHORT" : "FLOAT");
  } else if (name == "TEXCOORD_0") {
    const bool core = ct == 5126 || ((ct == 5121 || ct == 5123) && n);
    need("VEC2", core || (quant && ct != 5125),
         quant ? "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
               : "FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT");
  }
}

void Validator::meshes() {
  uint64_t total_vertices = 0, total_indices = 0;
  for (size_t i = 0; i < sizes_["meshes"]; ++i) {
    const json& m = at("meshes", i);
    const std::string p = "/meshes/" + std::to_string(i);
    const json* prims = opt(m, "primitives");
    if (!prims || !prims->is_array() || prims->empty() || prims->size() > lim_.max_primitives_per_mesh)
      fail(src_, p + "/primitives",
           "an array of 1 to " + std::to_string(lim_.max_primitives_per_mesh) + " primitives",
           prims ? show(*prims) : "nothing");
    for (size_t j = 0; j < prims->size(); ++j) {
      const json& pr = (*prims)[j];
      const std::string pp = p + "/primitives/" + std::to_string(j);
      if (!pr.is_object()) bad(pp, "an object", pr);
      primitive(pr, pp, total_vertices, total_indices);
    }
  }
}

void Validator::primitive(const json& pr, const std::string& pp, uint64_t& total_vertices,
                          uint64_t& total_indices) {
  const json* attrs = object(pr, "attributes", pp);
  if (!attrs || attrs->empty()) fail(src_, pp + "/attributes", "an object of attribute accessors", "nothing");
  const uint64_t mode = uint(pr, "mode", pp, false, 4, 0, 6);
  index(pr, "material", pp, "materials", false);
  const int indices = index(pr, "indices", pp, "accessors", false);
  const json* ext = object(pr, "extensions", pp);
  const json* draco = ext ? object(*ext, "KHR_draco_mesh_compression", pp + "/extensions") : nullptr;
  const std::string dp = pp + "/extensions/KHR_draco_mesh_compression";
  if (draco) {
    if (!used_.count("KHR_draco_mesh_compression"))
      fail(src_, dp, "KHR_draco_mesh_compression listed in /extensionsUsed", "it missing there");
    if (mode != 4)
      fail(src_, pp + "/mode", "4 (TRIANGLES) for a Draco-compressed primitive", std::to_string(mode));
    index(*draco, "bufferView", dp, "bufferViews", true);
    const json* da = object(*draco, "attributes", dp);
    if (!da) fail(src_, dp + "/attributes", "an object of Draco attribute ids", "nothing");
    for (auto it = da->begin(); it != da->end(); ++it) {
      const std::string ap = dp + "/attributes/" + pointer_key(it.key());
      if (!it->is_number_integer() || it->get<int64_t>() < 0 || it->get<int64_t>() > 1 << 20)
        bad(ap, "a Draco attribute unique id", *it);
      if (!attrs->contains(it.key()))
        fail(src_, ap, "an attribute also listed in the primitive's attributes",
             "\"" + it.key() + "\" only here");
    }
  }
  uint64_t count = 0;
  std::string first;
  for (auto it = attrs->begin(); it != attrs->end(); ++it) {
    const std::string ap = pp + "/attributes/" + pointer_key(it.key());
    const int a = index_value(*it, ap, "accessors");
    const bool in_draco = draco && (*draco)["attributes"].contains(it.key());
    if (!accessors_[a].has_view && !in_draco)
      fail(src_, ap, "an accessor with a bufferView (or a Draco-compressed attribute)",
           "accessor " + std::to_string(a) + " without bufferView");
    attribute_format(it.key(), a, ap);
    if (first.empty()) {
      first = it.key();
      count = accessors_[a].count;
    } else if (accessors_[a].count != count) {
      fail(src_, ap, "count " + std::to_string(count) + " like attribute " + first,
           "accessor " + std::to_string(a) + " with count " + std::to_string(accessors_[a].count));
    }
  }
  if (count > lim_.max_vertices_per_primitive)
    fail(src_, pp + "/attributes", "at most " + std::to_string(lim_.max_vertices_per_primitive) + " vertices",
         std::to_string(count));
  total_vertices += count;
  if (total_vertices > lim_.max_total_vertices)
    fail(src_, pp + "/attributes",
         "at most " + std::to_string(lim_.max_total_vertices) + " vertices in all meshes",
         std::to_string(total_vertices) + " so far");
  if (indices >= 0) {
    const AccessorInfo& a = accessors_[indices];
    if (a.type != "SCALAR" ||
        (a.component_type != 5121 && a.component_type != 5123 && a.component_type != 5125) || a.normalized)
      fail(src_, pp + "/indices", "a SCALAR accessor of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
           "accessor " + std::to_string(indices) + " of " + a.type + " componentType " +
               std::to_string(a.component_type));
    if (!a.has_view && !draco)
      fail(src_, pp + "/indices", "an accessor with a bufferView", "accessor " + std::to_string(indices));
    if (a.count > lim_.max_indices_per_primitive)
      fail(src_, pp + "/indices", "at most " + std::to_string(lim_.max_indices_per_primitive) + " indices",
           std::to_string(a.count));
    total_indices += a.count;
    if (total_indices > lim_.max_total_indices)
      fail(src_, pp + "/indices",
           "at most " + std::to_string(lim_.max_total_indices) + " indices in all meshes",
           std::to_string(total_indices) + " so far");
  } else {
    total_indices += count;
  }
  if (const json* targets = opt(pr, "targets")) {
    if (!targets->is_array() || targets->size() > 256)
      bad(pp + "/targets", "an array of morph targets", *targets);
    for (size_t t = 0; t < targets->size(); ++t) {
      const json& tg = (*targets)[t];
      const std::string tp = pp + "/targets/" + std::to_string(t);
      if (!tg.is_object()) bad(tp, "an object of accessors", tg);
      for (auto it = tg.begin(); it != tg.end(); ++it)
        index_value(*it, tp + "/" + pointer_key(it.key()), "accessors");
    }
  }
}

void Validator::nodes() {
  const size_t n = sizes_["nodes"];
  parents_.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const json& nd = at("nodes", i);
    const std::string p = "/nodes/" + std::to_string(i);
    index(nd, "mesh", p, "meshes", false);
    index(nd, "camera", p, "cameras", false);
    index(nd, "skin", p, "skins", false);
    number_array(nd, "matrix", p, 16, -HUGE_VAL, HUGE_VAL);
    number_array(nd, "translation", p, 3, -HUGE_VAL, HUGE_VAL);
    number_array(nd, "rotation", p, 4, -1.0, 1.0);
    number_array(nd, "scale", p, 3, -HUGE_VAL, HUGE_VAL);
    if (opt(nd, "matrix") && (opt(nd, "translation") || opt(nd, "rotation") || opt(nd, "scale")))
      fail(src_, p + "/matrix", "either matrix or translation/rotation/scale", "both");
    const json* ch = opt(nd, "children");
    if (!ch) continue;
    if (!ch->is_array()) bad(p + "/children", "an array of node indices", *ch);
    for (size_t k = 0; k < ch->size(); ++k) {
      const std::string cp = p + "/children/" + std::to_string(k);
      const int c = index_value((*ch)[k], cp, "nodes");
      if (size_t(c) == i) fail(src_, cp, "another node", "the node itself");
      if (parents_[c] >= 0)
        fail(src_, cp, "a node with one parent",
             "node " + std::to_string(c) + ", already a child of node " + std::to_string(parents_[c]));
      parents_[c] = int(i);
    }
  }
  // With one parent each, a node is in a cycle exactly when walking up never reaches a root.
  std::vector<int> state(n, 0);  // 0 unknown, 1 reaches a root, 2 on the current walk
  for (size_t i = 0; i < n; ++i) {
    std::vector<size_t> walk;
    size_t k = i;
    while (state[k] == 0) {
      state[k] = 2;
      walk.push_back(k);
      if (parents_[k] < 0) break;
      k = size_t(parents_[k]);
    }
    if (state[k] == 2 && parents_[k] >= 0)
      fail(src_, "/nodes/" + std::to_string(k) + "/children", "a tree of nodes",
           "a cycle through node " + std::to_string(k));
    for (size_t w : walk) state[w] = 1;
  }
}

void Validator::scenes() {
  // Marks of the roots listed by the scene being checked, cleared after each scene: one array for
  // all scenes (an array per scene would cost scenes x nodes).
  std::vector<bool> listed(parents_.size(), false);
  std::vector<int> marked;
  for (size_t i = 0; i < sizes_["scenes"]; ++i) {
    const json& s = at("scenes", i);
    const std::string p = "/scenes/" + std::to_string(i);
    const json* ns = opt(s, "nodes");
    if (!ns) continue;
    if (!ns->is_array()) bad(p + "/nodes", "an array of root node indices", *ns);
    for (int nd : marked) listed[size_t(nd)] = false;
    marked.clear();
    for (size_t k = 0; k < ns->size(); ++k) {
      const std::string np = p + "/nodes/" + std::to_string(k);
      const int nd = index_value((*ns)[k], np, "nodes");
      if (parents_[nd] >= 0)
        fail(src_, np, "a root node",
             "node " + std::to_string(nd) + ", a child of node " + std::to_string(parents_[nd]));
      if (listed[size_t(nd)]) fail(src_, np, "each root node once", "node " + std::to_string(nd) + " again");
      listed[size_t(nd)] = true;  // the spec requires each root once per scene
      marked.push_back(nd);
    }
  }
  index(doc_, "scene", "", "scenes", false);
}

}  // namespace welkin::assets::detail
