// Loop / Catmull-Clark refinement with OpenSubdiv: Far topology + Osd CPU stencils for uniform levels,
// Bfr limit-surface tessellation with shared edge rates for distance-adaptive output.
#include "welkin/assets/subdivision.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/osd/cpuEvaluator.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "welkin/core/error.h"

namespace welkin::assets {

namespace {

using namespace OpenSubdiv;

constexpr size_t kMaxControlFaces = size_t(1) << 24;
constexpr int kMaxLevels = 10;  // Far stores the level in 4 bits; 10 keeps counts far from overflow

[[noreturn]] void bad(const std::string& path, const std::string& expected, const std::string& found) {
  throw Error(ErrorInfo{.file = "", .path = path, .expected = expected, .found = found});
}

SubdivScheme resolve_scheme(const ControlMesh& m, SubdivScheme s) {
  const bool all_tris = std::all_of(m.face_sizes.begin(), m.face_sizes.end(), [](int n) { return n == 3; });
  if (s == SubdivScheme::automatic) return all_tris ? SubdivScheme::loop : SubdivScheme::catmull_clark;
  if (s == SubdivScheme::loop && !all_tris) {
    const auto it = std::find_if(m.face_sizes.begin(), m.face_sizes.end(), [](int n) { return n != 3; });
    bad("/face_sizes/" + std::to_string(it - m.face_sizes.begin()), "3 (Loop subdivides triangles only)",
        std::to_string(*it));
  }
  return s;
}

void validate(const ControlMesh& m) {
  if (m.face_sizes.empty() || m.face_sizes.size() > kMaxControlFaces)
    bad("/face_sizes", "1 to " + std::to_string(kMaxControlFaces) + " faces",
        std::to_string(m.face_sizes.size()));
  if (m.positions.size() > kMaxControlFaces * 4)
    bad("/positions", "at most " + std::to_string(kMaxControlFaces * 4) + " vertices",
        std::to_string(m.positions.size()));
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!std::isfinite(m.positions[i].x) || !std::isfinite(m.positions[i].y) ||
        !std::isfinite(m.positions[i].z))
      bad("/positions/" + std::to_string(i), "finite coordinates", "a NaN or infinity");
  size_t offset = 0;
  for (size_t f = 0; f < m.face_sizes.size(); ++f) {
    const int n = m.face_sizes[f];
    if (n < 3 || n > 64) bad("/face_sizes/" + std::to_string(f), "3 to 64 vertices", std::to_string(n));
    if (offset + size_t(n) > m.face_indices.size())
      bad("/face_indices", "the sum of face_sizes (" + std::to_string(offset + n) + "+) indices",
          std::to_string(m.face_indices.size()));
    for (int k = 0; k < n; ++k) {
      const int v = m.face_indices[offset + k];
      if (v < 0 || size_t(v) >= m.positions.size())
        bad("/face_indices/" + std::to_string(offset + k),
            "a vertex index below " + std::to_string(m.positions.size()), std::to_string(v));
      for (int j = 0; j < k; ++j)
        if (m.face_indices[offset + j] == v)
          bad("/face_indices/" + std::to_string(offset + k),
              "distinct vertices within face " + std::to_string(f), "vertex " + std::to_string(v) + " twice");
    }
    offset += size_t(n);
  }
  if (offset != m.face_indices.size())
    bad("/face_indices", std::to_string(offset) + " indices (the sum of face_sizes)",
        std::to_string(m.face_indices.size()));
}

std::unique_ptr<Far::TopologyRefiner> make_refiner(const ControlMesh& m, SubdivScheme scheme,
                                                   bool sharp_corners) {
  Far::TopologyDescriptor desc;
  desc.numVertices = int(m.positions.size());
  desc.numFaces = int(m.face_sizes.size());
  desc.numVertsPerFace = m.face_sizes.data();
  desc.vertIndicesPerFace = m.face_indices.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(sharp_corners ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  Factory::Options options(scheme == SubdivScheme::loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK, sdc);
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, options));
  if (!r) bad("", "a mesh topology OpenSubdiv accepts", "one it rejected");
  return r;
}

// Triangles after `level` uniform levels: Loop quarters triangles; CC makes n quads of an n-gon, then
// quarters quads; each quad is 2 triangles, an unrefined n-gon a fan of n - 2.
uint64_t uniform_triangles(const ControlMesh& m, SubdivScheme scheme, int level) {
  uint64_t t = 0;
  for (int n : m.face_sizes) {
    if (scheme == SubdivScheme::loop)
      t += uint64_t(1) << (2 * level);
    else
      t += level == 0 ? uint64_t(n - 2) : 2 * uint64_t(n) << (2 * (level - 1));
  }
  return t;
}

// Minimal primvar type for Far::PrimvarRefiner.
struct P3 {
  float v[3];
  void Clear(void* = nullptr) { v[0] = v[1] = v[2] = 0.0f; }
  void AddWithWeight(const P3& s, float w) { v[0] += w * s.v[0], v[1] += w * s.v[1], v[2] += w * s.v[2]; }
};

std::vector<glm::vec3> face_normals_average(const std::vector<glm::vec3>& pos,
                                            const std::vector<uint32_t>& idx) {
  std::vector<glm::vec3> n(pos.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::vec3 fn = glm::cross(pos[idx[t + 1]] - pos[idx[t]], pos[idx[t + 2]] - pos[idx[t]]);
    for (int k = 0; k < 3; ++k) n[idx[t + k]] += fn;
  }
  for (glm::vec3& v : n) {
    const float l = glm::length(v);
    v = l > 0.0f ? v / l : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return n;
}

RefinedMesh refine_uniform(const ControlMesh& m, SubdivScheme scheme, const RefineSettings& s) {
  int level = std::clamp(s.levels, 0, kMaxLevels);
  while (level > 0 && uniform_triangles(m, scheme, level) > s.max_triangles) --level;
  if (uniform_triangles(m, scheme, level) > s.max_triangles)
    bad("/max_triangles",
        "a budget of at least " + std::to_string(uniform_triangles(m, scheme, 0)) +
            " triangles (the unrefined mesh)",
        std::to_string(s.max_triangles));
  auto refiner = make_refiner(m, scheme, s.sharp_boundary_corners);
  Far::TopologyRefiner::UniformOptions uo(level);
  uo.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uo);

  RefinedMesh out;
  out.scheme = scheme;
  out.level = level;
  const Far::TopologyLevel& last = refiner->GetLevel(level);
  std::vector<P3> fine(size_t(last.GetNumVertices()));
  if (level == 0) {
    for (size_t i = 0; i < fine.size(); ++i)
      fine[i] = P3{{m.positions[i].x, m.positions[i].y, m.positions[i].z}};
  } else {
    // Control points to the finest level in one pass of Far stencils evaluated by the Osd CPU kernel.
    // The float template itself: the Far::StencilTableFactory wrapper static_casts the table it
    // built (a StencilTableReal<float>) down to Far::StencilTable, which UBSan reports as an invalid
    // downcast; nothing here needs the derived type.
    using Factory = Far::StencilTableFactoryReal<float>;
    Factory::Options so;
    so.generateIntermediateLevels = false;
    so.generateOffsets = true;
    std::unique_ptr<const Far::StencilTableReal<float>> st(Factory::Create(*refiner, so));
    Osd::BufferDescriptor desc(0, 3, 3);
    Osd::CpuEvaluator::EvalStencils(&m.positions[0].x, desc, fine[0].v, desc, st->GetSizes().data(),
                                    st->GetOffsets().data(), st->GetControlIndices().data(),
                                    st->GetWeights().data(), 0, st->GetNumStencils());
  }
  std::vector<P3> tan1, tan2;
  if (s.limit_surface) {
    std::vector<P3> limit(fine.size());
    tan1.resize(fine.size());
    tan2.resize(fine.size());
    Far::PrimvarRefiner(*refiner).Limit(fine, limit, tan1, tan2);
    fine.swap(limit);
  }
  out.positions.resize(fine.size());
  for (size_t i = 0; i < fine.size(); ++i)
    out.positions[i] = glm::vec3(fine[i].v[0], fine[i].v[1], fine[i].v[2]);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto fv = last.GetFaceVertices(f);
    for (int k = 1; k + 1 < fv.size(); ++k)
      out.indices.insert(out.indices.end(), {uint32_t(fv[0]), uint32_t(fv[k]), uint32_t(fv[k + 1])});
  }
  out.normals = face_normals_average(out.positions, out.indices);
  if (s.limit_surface) {
    // Limit tangents give the exact normal; the averaged one only picks its side.
    for (size_t i = 0; i < fine.size(); ++i) {
      const glm::vec3 n = glm::cross(glm::vec3(tan1[i].v[0], tan1[i].v[1], tan1[i].v[2]),
                                     glm::vec3(tan2[i].v[0], tan2[i].v[1], tan2[i].v[2]));
      const float l = glm::length(n);
      if (l > 1e-20f && std::isfinite(l))
        out.normals[i] = glm::dot(n, out.normals[i]) < 0.0f ? -n / l : n / l;
    }
  }
  return out;
}

RefinedMesh refine_adaptive(const ControlMesh& m, SubdivScheme scheme, const RefineSettings& s) {
  auto refiner = make_refiner(m, scheme, s.sharp_boundary_corners);
  const Far::TopologyLevel& base = refiner->GetLevel(0);
  const int max_level = std::clamp(s.levels, 0, kMaxLevels);
  // Level of an edge from its midpoint's distance: full within adaptive_distance, one less per doubling.
  std::vector<int> edge_level(size_t(base.GetNumEdges()));
  for (int e = 0; e < base.GetNumEdges(); ++e) {
    const auto ev = base.GetEdgeVertices(e);
    const glm::vec3 mid = 0.5f * (m.positions[size_t(ev[0])] + m.positions[size_t(ev[1])]);
    const double ratio = std::max(1.0, double(glm::length(mid - s.camera_position)) / s.adaptive_distance);
    // Clamped while still a double: far points (or a tiny distance) make the ratio infinite, and
    // converting infinity to int is undefined (UBSan found it).
    const double doublings = std::floor(std::log2(ratio));
    edge_level[size_t(e)] = doublings < double(max_level) ? max_level - int(doublings) : 0;
  }
  Bfr::Tessellation::Options topts;
  topts.SetFacetSize(3);
  auto rates_of = [&](int f, int drop, int* rates) {
    const auto fe = base.GetFaceEdges(f);
    for (int k = 0; k < fe.size(); ++k) rates[k] = 1 << std::max(edge_level[size_t(fe[k])] - drop, 0);
    return fe.size();
  };
  // Lower every level until the budget holds (facet counts need no evaluation).
  int drop = 0;
  for (;; ++drop) {
    uint64_t facets = 0;
    int rates[64];
    for (int f = 0; f < base.GetNumFaces(); ++f) {
      const int n = rates_of(f, drop, rates);
      Bfr::Tessellation t(
          Bfr::Parameterization(scheme == SubdivScheme::loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK, n), n,
          rates, topts);
      facets += uint64_t(t.GetNumFacets());
    }
    if (facets <= s.max_triangles) break;
    if (drop >= max_level)
      bad("/max_triangles",
          "a budget of at least " + std::to_string(facets) + " triangles (all edges at level 0)",
          std::to_string(s.max_triangles));
  }

  Bfr::RefinerSurfaceFactory<> factory(*refiner);
  Bfr::Surface<float> surface;
  RefinedMesh out;
  out.scheme = scheme;
  out.adaptive = true;
  out.level = std::max(max_level - drop, 0);
  std::vector<int> corner_index(m.positions.size(), -1), edge_start(size_t(base.GetNumEdges()), -1);
  std::vector<float> patch_points, coords;
  std::vector<int> facets, boundary;
  std::vector<glm::vec3> du_sum;
  auto add_vertex = [&](int& slot) {
    if (slot >= 0) return false;
    slot = int(out.positions.size());
    out.positions.emplace_back(0.0f);
    out.normals.emplace_back(0.0f);
    return true;
  };
  for (int f = 0; f < base.GetNumFaces(); ++f) {
    if (!factory.InitVertexSurface(f, &surface)) continue;  // a hole
    int rates[64];
    const int n = rates_of(f, drop, rates);
    Bfr::Tessellation tess(surface.GetParameterization(), n, rates, topts);
    patch_points.resize(size_t(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(&m.positions[0].x, 3, patch_points.data(), 3);
    coords.resize(size_t(tess.GetNumCoords()) * 2);
    tess.GetCoords(coords.data());
    // Boundary coords run vertex 0, edge 0's inner points, vertex 1, ...: map them to shared indices so
    // neighbours reuse one vertex per corner and per edge point (no cracks between faces).
    const auto fv = base.GetFaceVertices(f);
    const auto fe = base.GetFaceEdges(f);
    boundary.assign(size_t(tess.GetNumBoundaryCoords()), -1);
    std::vector<char> fresh(size_t(tess.GetNumCoords()), 0);
    size_t b = 0;
    for (int k = 0; k < n; ++k) {
      fresh[b] = add_vertex(corner_index[size_t(fv[k])]);
      boundary[b++] = corner_index[size_t(fv[k])];
      const int inner = rates[k] - 1;
      int& start = edge_start[size_t(fe[k])];
      const bool created = start < 0;
      if (created) {
        start = int(out.positions.size());
        for (int j = 0; j < inner; ++j) {
          out.positions.emplace_back(0.0f);
          out.normals.emplace_back(0.0f);
        }
      }
      const bool forward = base.GetEdgeVertices(fe[k])[0] == fv[k];
      for (int j = 0; j < inner; ++j) {
        fresh[b] = created;
        boundary[b++] = start + (forward ? j : inner - 1 - j);
      }
    }
    const int interior_offset = int(out.positions.size()) - tess.GetNumBoundaryCoords();
    for (int j = tess.GetNumBoundaryCoords(); j < tess.GetNumCoords(); ++j) {
      out.positions.emplace_back(0.0f);
      out.normals.emplace_back(0.0f);
      fresh[size_t(j)] = 1;
    }
    for (int j = 0; j < tess.GetNumCoords(); ++j) {
      if (!fresh[size_t(j)]) continue;
      const size_t dst = size_t(j < tess.GetNumBoundaryCoords() ? boundary[size_t(j)] : interior_offset + j);
      float p[3], du[3], dv[3];
      surface.Evaluate(&coords[size_t(j) * 2], patch_points.data(), 3, p, du, dv);
      out.positions[dst] = glm::vec3(p[0], p[1], p[2]);
      out.normals[dst] = glm::cross(glm::vec3(du[0], du[1], du[2]), glm::vec3(dv[0], dv[1], dv[2]));
    }
    facets.resize(size_t(tess.GetNumFacets()) * 3);
    tess.GetFacets(facets.data());
    tess.TransformFacetCoordIndices(facets.data(), boundary.data(), interior_offset);
    for (int idx : facets) out.indices.push_back(uint32_t(idx));
  }
  const std::vector<glm::vec3> avg = face_normals_average(out.positions, out.indices);
  for (size_t i = 0; i < out.normals.size(); ++i) {
    const float l = glm::length(out.normals[i]);
    out.normals[i] = l > 1e-20f && std::isfinite(l) ? out.normals[i] / l : avg[i];
  }
  return out;
}

}  // namespace

RefinedMesh refine(const ControlMesh& mesh, const RefineSettings& settings) {
  validate(mesh);
  if (settings.levels < 0 || settings.levels > kMaxLevels)
    bad("/levels", "0 to " + std::to_string(kMaxLevels), std::to_string(settings.levels));
  if (!std::isfinite(settings.camera_position.x) || !std::isfinite(settings.camera_position.y) ||
      !std::isfinite(settings.camera_position.z))
    bad("/camera_position", "finite coordinates", "a NaN or infinity");
  if (!std::isfinite(settings.adaptive_distance) || settings.adaptive_distance < 0.0f)
    bad("/adaptive_distance", "0 (uniform) or a positive distance",
        std::to_string(settings.adaptive_distance));
  const SubdivScheme scheme = resolve_scheme(mesh, settings.scheme);
  return settings.adaptive_distance > 0.0f ? refine_adaptive(mesh, scheme, settings)
                                           : refine_uniform(mesh, scheme, settings);
}

std::vector<LevelCounts> uniform_level_counts(const ControlMesh& mesh, SubdivScheme scheme, int levels) {
  validate(mesh);
  if (levels < 0 || levels > kMaxLevels)
    bad("/levels", "0 to " + std::to_string(kMaxLevels), std::to_string(levels));
  scheme = resolve_scheme(mesh, scheme);
  if (uniform_triangles(mesh, scheme, levels) > (uint64_t(1) << 28))
    bad("/levels", "at most 2^28 triangles at the last level",
        std::to_string(uniform_triangles(mesh, scheme, levels)));
  auto refiner = make_refiner(mesh, scheme, true);
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
  std::vector<LevelCounts> out;
  for (int l = 0; l <= levels; ++l)
    out.push_back({refiner->GetLevel(l).GetNumVertices(), refiner->GetLevel(l).GetNumFaces()});
  return out;
}

}  // namespace welkin::assets
