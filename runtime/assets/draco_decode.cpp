// KHR_draco_mesh_compression streams decoded with Draco, every index checked before it is followed.
#include <draco/compression/decode.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/varint_decoding.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

#include <cmath>
#include <limits>

#include "internal.h"

namespace welkin::assets::detail {

struct DracoDecoder::Impl {
  std::unique_ptr<draco::Mesh> mesh;
};

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

}  // namespace

DracoDecoder::DracoDecoder(std::span<const uint8_t> stream, const DracoExpected& expected, const Source& src,
                           const std::string& path)
    : impl_(new Impl), src_(src) {
  try {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
    check_draco_counts(read_draco_counts(buffer, src, path), expected, src, path);
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok())
      fail(src, path, "a valid Draco mesh stream",
           std::string("a decoding error (") + result.status().error_msg() + ")");
    impl_->mesh = std::move(result).value();
    const draco::Mesh& m = *impl_->mesh;
    const auto& lim = src.options.limits;
    if (m.num_points() > lim.max_vertices_per_primitive)
      fail(src, path, "at most " + std::to_string(lim.max_vertices_per_primitive) + " vertices",
           std::to_string(m.num_points()) + " decoded");
    if (uint64_t(m.num_faces()) * 3 > lim.max_indices_per_primitive)
      fail(src, path, "at most " + std::to_string(lim.max_indices_per_primitive) + " indices",
           std::to_string(uint64_t(m.num_faces()) * 3) + " decoded");
    mesh_.num_points = m.num_points();
    mesh_.indices.resize(size_t(m.num_faces()) * 3);
    for (draco::FaceIndex f(0); f < m.num_faces(); ++f) {
      const auto& face = m.face(f);
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = face[k].value();
        if (v >= mesh_.num_points)
          fail(src, path, "face indices below the " + std::to_string(mesh_.num_points) + " decoded points",
               "index " + std::to_string(v) + " in face " + std::to_string(f.value()));
        mesh_.indices[size_t(f.value()) * 3 + k] = v;
      }
    }
  } catch (...) {
    delete impl_;
    throw;
  }
}

DracoDecoder::~DracoDecoder() {
  delete impl_;
}

DracoAttribute DracoDecoder::attribute(int unique_id, int components, int component_type, bool normalized,
                                       const std::string& path) const {
  const draco::Mesh& m = *impl_->mesh;
  const draco::PointAttribute* a = m.GetAttributeByUniqueId(uint32_t(unique_id));
  if (!a) fail(src_, path, "a Draco attribute id present in the stream", std::to_string(unique_id));
  if (a->num_components() != components)
    fail(src_, path, std::to_string(components) + " components (the accessor's type)",
         std::to_string(int(a->num_components())) + " in Draco attribute " + std::to_string(unique_id));
  const uint32_t n = m.num_points();
  if (a->is_mapping_identity() ? a->size() < n : a->indices_map_size() < n)
    fail(src_, path, "a Draco attribute covering all " + std::to_string(n) + " points",
         "attribute " + std::to_string(unique_id) + " with fewer entries");
  DracoAttribute out;
  out.components = components;
  out.values.resize(size_t(n) * components);
  // Integer accessors carry integer values that glTF's normalization then maps to floats.
  double lo = 0, hi = 0, scale = 0;
  switch (component_type) {
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
      fail(src_, path, "attribute entries below " + std::to_string(a->size()),
           "entry " + std::to_string(v.value()) + " for point " + std::to_string(p.value()));
    float* dst = &out.values[size_t(p.value()) * components];
    bool ok;
    if (component_type == 5126) {
      ok = a->ConvertValue<float>(v, int8_t(components), dst);
    } else {
      int32_t raw[4] = {0, 0, 0, 0};
      ok = a->ConvertValue<int32_t>(v, int8_t(components), raw);
      for (int c = 0; ok && c < components; ++c) {
        if (raw[c] < lo || raw[c] > hi) ok = false;
        dst[c] = normalized ? std::max(float(raw[c] / scale), -1.0f) : float(raw[c]);
      }
    }
    for (int c = 0; ok && c < components; ++c) ok = std::isfinite(dst[c]);
    if (!ok)
      fail(src_, path,
           "Draco values representable in the accessor's component type " + std::to_string(component_type),
           "an unconvertible value at point " + std::to_string(p.value()));
  }
  return out;
}

}  // namespace welkin::assets::detail
