// KHR_draco_mesh_compression streams decoded with Draco, every index checked before it is followed.
#include <draco/compression/decode.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/varint_decoding.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "internal.h"
#include "welkin/core/child_process.h"

namespace welkin::assets::detail {

namespace {

// Face and vertex counts as the stream's connectivity header states them (Draco bitstream 2.2, the
// version KHR_draco_mesh_compression is based on). Draco sizes its corner table and attribute
// buffers from these counts; reading them first (with Draco's own header, metadata and varint
// decoders) bounds that work by LoadLimits and the accessors whatever checks Draco's version makes,
// and names the limit in the error.
struct DracoCounts {
  uint32_t faces = 0;
  uint32_t vertices = 0;      // sequential: points; edgebreaker: encoded vertices (at most the points)
  bool exact_points = false;  // true when `vertices` is the decoded point count itself (sequential)
};

DracoCounts read_draco_counts(draco::DecoderBuffer buffer, const Source& src, const std::string& path) {
  draco::DracoHeader header;
  if (const draco::Status st = draco::PointCloudDecoder::DecodeHeader(&buffer, &header); !st.ok())
    fail(src, path, "a Draco stream", std::string("a bad header (") + st.error_msg() + ")");
  if (header.encoder_type != draco::TRIANGULAR_MESH)
    fail(src, path, "a Draco triangle mesh", "a Draco point cloud or unknown geometry");
  if (header.version_major != 2 || header.version_minor < 2)
    fail(src, path, "a Draco bitstream of version 2.2 or later (KHR_draco_mesh_compression)",
         "version " + std::to_string(header.version_major) + "." + std::to_string(header.version_minor));
  buffer.set_bitstream_version(DRACO_BITSTREAM_VERSION(header.version_major, header.version_minor));
  if (header.flags & METADATA_FLAG_MASK) {
    draco::GeometryMetadata metadata;
    if (!draco::MetadataDecoder().DecodeGeometryMetadata(&buffer, &metadata))
      fail(src, path, "a valid Draco stream", "undecodable metadata");
  }
  DracoCounts c;
  bool ok = false;
  if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
    ok = draco::DecodeVarint(&c.faces, &buffer) && draco::DecodeVarint(&c.vertices, &buffer);
    c.exact_points = true;
  } else if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) {
    uint8_t traversal = 0;
    ok = buffer.Decode(&traversal) && draco::DecodeVarint(&c.vertices, &buffer) &&
         draco::DecodeVarint(&c.faces, &buffer);
  } else {
    fail(src, path, "a Draco sequential or edgebreaker mesh",
         "encoding method " + std::to_string(int(header.encoder_method)));
  }
  if (!ok) fail(src, path, "a valid Draco stream", "a connectivity header cut short");
  return c;
}

// The header's counts against the limits and the accessors, before any decoding.
void check_draco_counts(const DracoCounts& c, const DracoExpected& expected, const Source& src,
                        const std::string& path) {
  const auto& lim = src.options.limits;
  const uint64_t indices = uint64_t(c.faces) * 3;
  if (indices > lim.max_indices_per_primitive)
    fail(src, path, "at most " + std::to_string(lim.max_indices_per_primitive) + " indices",
         std::to_string(indices) + " (" + std::to_string(c.faces) + " faces in the Draco header)");
  if (c.vertices > lim.max_vertices_per_primitive)
    fail(src, path, "at most " + std::to_string(lim.max_vertices_per_primitive) + " vertices",
         std::to_string(c.vertices) + " in the Draco header");
  if (expected.indices >= 0 && indices != uint64_t(expected.indices))
    fail(src, path, std::to_string(expected.indices) + " indices (the indices accessor's count)",
         std::to_string(indices) + " (" + std::to_string(c.faces) + " faces in the Draco header)");
  // Edgebreaker may split a vertex into several points (attribute seams), never the reverse.
  if (c.exact_points ? c.vertices != expected.points : c.vertices > expected.points)
    fail(src, path, std::to_string(expected.points) + " vertices (the attribute accessors' count)",
         std::to_string(c.vertices) + " in the Draco header");
}

// One attribute of the decoded mesh, converted as its request says.
DracoAttribute read_attribute(const draco::Mesh& m, const DracoRequest& r, const Source& src) {
  const draco::PointAttribute* a = m.GetAttributeByUniqueId(uint32_t(r.unique_id));
  if (!a) fail(src, r.path, "a Draco attribute id present in the stream", std::to_string(r.unique_id));
  if (a->num_components() != r.components)
    fail(src, r.path, std::to_string(r.components) + " components (the accessor's type)",
         std::to_string(int(a->num_components())) + " in Draco attribute " + std::to_string(r.unique_id));
  const uint32_t n = m.num_points();
  if (a->is_mapping_identity() ? a->size() < n : a->indices_map_size() < n)
    fail(src, r.path, "a Draco attribute covering all " + std::to_string(n) + " points",
         "attribute " + std::to_string(r.unique_id) + " with fewer entries");
  DracoAttribute out;
  out.components = r.components;
  out.values.resize(size_t(n) * r.components);
  // Integer accessors carry integer values that glTF's normalization then maps to floats.
  double lo = 0, hi = 0, scale = 0;
  switch (r.component_type) {
    case 5120:
      lo = -128, hi = 127, scale = 127;
      break;
    case 5121:
      lo = 0, hi = 255, scale = 255;
      break;
    case 5122:
      lo = -32768, hi = 32767, scale = 32767;
      break;
    case 5123:
      lo = 0, hi = 65535, scale = 65535;
      break;
    default:
      break;
  }
  for (draco::PointIndex p(0); p < n; ++p) {
    const draco::AttributeValueIndex v = a->mapped_index(p);
    if (v.value() >= a->size())
      fail(src, r.path, "attribute entries below " + std::to_string(a->size()),
           "entry " + std::to_string(v.value()) + " for point " + std::to_string(p.value()));
    float* dst = &out.values[size_t(p.value()) * r.components];
    bool ok;
    if (r.component_type == 5126) {
      ok = a->ConvertValue<float>(v, int8_t(r.components), dst);
    } else {
      int32_t raw[4] = {0, 0, 0, 0};
      ok = a->ConvertValue<int32_t>(v, int8_t(r.components), raw);
      for (int c = 0; ok && c < r.components; ++c) {
        if (raw[c] < lo || raw[c] > hi) ok = false;
        dst[c] = r.normalized ? std::max(float(raw[c] / scale), -1.0f) : float(raw[c]);
      }
    }
    for (int c = 0; ok && c < r.components; ++c) ok = std::isfinite(dst[c]);
    if (!ok)
      fail(src, r.path,
           "Draco values representable in the accessor's component type " + std::to_string(r.component_type),
           "an unconvertible value at point " + std::to_string(p.value()));
  }
  return out;
}

// Draco's decode and everything read from its mesh (runs in the child process).
DracoMesh decode_in_this_process(draco::DecoderBuffer buffer, const DracoExpected& expected,
                                 const Source& src, const std::string& path) {
  draco::Decoder decoder;
  auto result = decoder.DecodeMeshFromBuffer(&buffer);
  if (!result.ok())
    fail(src, path, "a valid Draco mesh stream",
         std::string("a decoding error (") + result.status().error_msg() + ")");
  const draco::Mesh& m = *result.value();
  const auto& lim = src.options.limits;
  if (m.num_points() > lim.max_vertices_per_primitive)
    fail(src, path, "at most " + std::to_string(lim.max_vertices_per_primitive) + " vertices",
         std::to_string(m.num_points()) + " decoded");
  if (uint64_t(m.num_faces()) * 3 > lim.max_indices_per_primitive)
    fail(src, path, "at most " + std::to_string(lim.max_indices_per_primitive) + " indices",
         std::to_string(uint64_t(m.num_faces()) * 3) + " decoded");
  DracoMesh mesh;
  mesh.num_points = m.num_points();
  mesh.indices.resize(size_t(m.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < m.num_faces(); ++f) {
    const auto& face = m.face(f);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = face[k].value();
      if (v >= mesh.num_points)
        fail(src, path, "face indices below the " + std::to_string(mesh.num_points) + " decoded points",
             "index " + std::to_string(v) + " in face " + std::to_string(f.value()));
      mesh.indices[size_t(f.value()) * 3 + k] = v;
    }
  }
  for (const DracoRequest& r : expected.attributes) mesh.attributes[r.name] = read_attribute(m, r, src);
  return mesh;
}

// The child's answer through the pipe: a mesh, or the Error it threw.
enum : uint8_t { kMesh = 0, kError = 1 };

struct Writer {
  std::vector<uint8_t> bytes;
  void raw(const void* p, size_t n) {
    bytes.insert(bytes.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
  }
  void u64(uint64_t v) { raw(&v, sizeof v); }
  void text(const std::string& s) { u64(s.size()), raw(s.data(), s.size()); }
};

struct Reader {
  std::span<const uint8_t> bytes;
  size_t at = 0;
  bool ok = true;
  void raw(void* p, size_t n) {
    if (!ok || n > bytes.size() - at) {
      ok = false;
      return;
    }
    std::memcpy(p, bytes.data() + at, n), at += n;
  }
  uint64_t u64() {
    uint64_t v = 0;
    raw(&v, sizeof v);
    return v;
  }
  // A count of `size`-byte items that the remaining bytes can hold.
  size_t count(size_t size) {
    const uint64_t n = u64();
    if (!ok || n > (bytes.size() - at) / size) ok = false;
    return ok ? size_t(n) : 0;
  }
  std::string text() {
    std::string s(count(1), '\0');
    raw(s.data(), s.size());
    return s;
  }
};

std::vector<uint8_t> encode(const DracoMesh& m) {
  Writer w;
  w.bytes.push_back(kMesh);
  w.u64(m.num_points);
  w.u64(m.indices.size()), w.raw(m.indices.data(), m.indices.size() * sizeof(uint32_t));
  w.u64(m.attributes.size());
  for (const auto& [name, a] : m.attributes) {
    w.text(name), w.u64(uint64_t(a.components));
    w.u64(a.values.size()), w.raw(a.values.data(), a.values.size() * sizeof(float));
  }
  return std::move(w.bytes);
}

std::vector<uint8_t> encode(const ErrorInfo& e) {
  Writer w;
  w.bytes.push_back(kError);
  for (const std::string* s : {&e.path, &e.expected, &e.found, &e.message}) w.text(*s);
  return std::move(w.bytes);
}

}  // namespace

DracoMesh decode_draco(std::span<const uint8_t> stream, const DracoExpected& expected, const Source& src,
                       const std::string& path) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
  const DracoCounts counts = read_draco_counts(buffer, src, path);
  check_draco_counts(counts, expected, src, path);
  // The budget grows with the mesh the header declares (already within LoadLimits).
  const auto& lim = src.options.limits;
  const uint64_t elements = uint64_t(counts.faces) + std::max<uint64_t>(counts.vertices, expected.points);
  ChildLimits limits;
  limits.seconds = lim.draco_seconds + lim.draco_seconds_per_element * double(elements);
  limits.memory_bytes = lim.draco_memory_bytes + lim.draco_memory_bytes_per_element * elements;
  uint64_t floats = 0;
  for (const DracoRequest& r : expected.attributes) floats += expected.points * uint64_t(r.components);
  limits.max_result_bytes =
      (1u << 16) + uint64_t(counts.faces) * 3 * sizeof(uint32_t) + floats * sizeof(float);
  const ChildResult child = run_in_child(
      [&] {
        try {
          return encode(decode_in_this_process(buffer, expected, src, path));
        } catch (const Error& e) {
          return encode(e.info());
        }
      },
      limits);
  if (child.status != ChildResult::Status::ok)
    fail(src, path, "a Draco stream that decodes within its budget", describe(child, limits));
  Reader r{child.bytes};
  uint8_t kind = 0xff;
  r.raw(&kind, 1);
  if (kind == kError) {
    ErrorInfo info;
    info.file = src.name;
    for (std::string* s : {&info.path, &info.expected, &info.found, &info.message}) *s = r.text();
    if (r.ok) throw Error(info);
  }
  DracoMesh mesh;
  if (kind == kMesh) {
    const uint64_t points = r.u64();
    mesh.num_points = uint32_t(points);
    r.ok = r.ok && points == mesh.num_points;
    mesh.indices.resize(r.count(sizeof(uint32_t)));
    r.raw(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    for (size_t n = r.count(1); r.ok && n > 0; --n) {
      const std::string name = r.text();
      DracoAttribute& a = mesh.attributes[name];
      a.components = int(r.u64());
      a.values.resize(r.count(sizeof(float)));
      r.raw(a.values.data(), a.values.size() * sizeof(float));
    }
  }
  if (!r.ok || (kind != kMesh && kind != kError) || r.at != r.bytes.size())
    fail(src, path, "a Draco stream that decodes", "a malformed answer from the decoding process");
  return mesh;
}

}  // namespace welkin::assets::detail
