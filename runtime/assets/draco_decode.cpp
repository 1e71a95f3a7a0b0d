// KHR_draco_mesh_compression streams decoded with Draco, every index checked before it is followed.
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <cmath>
#include <limits>

#include "internal.h"

namespace welkin::assets::detail {

struct DracoDecoder::Impl {
  std::unique_ptr<draco::Mesh> mesh;
};

DracoDecoder::DracoDecoder(std::span<const uint8_t> stream, const Source& src, const std::string& path)
    : impl_(new Impl), src_(src) {
  try {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok())
      fail(src, path, "a Draco stream", std::string("a bad header (") + type.status().error_msg() + ")");
    if (type.value() != draco::TRIANGULAR_MESH)
      fail(src, path, "a Draco triangle mesh", "a Draco point cloud or unknown geometry");
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
