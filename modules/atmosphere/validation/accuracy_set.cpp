#include "validation/accuracy_set.h"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "reference/path_tracer.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/scene/json_fields.h"

namespace welkin::atmosphere {

namespace {

using nlohmann::json;
namespace ref = reference;

std::string key(const ref::ProbeGeometry& g) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.9g/%.9g/%.9g/%.9g/%.9g", g.altitude_km, g.view_zenith_deg,
                g.view_azimuth_deg, g.sun_zenith_deg, g.sun_azimuth_deg);
  return buf;
}

json rgb(const glm::dvec3& v) {
  return json::array({v.x, v.y, v.z});
}
glm::dvec3 rgb(const json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

json profile(const ref::DensityProfile& p) {
  json layers = json::array();
  for (const ref::DensityLayer& l : p.layers)
    layers.push_back({l.width_km, l.exp_term, l.exp_scale_per_km, l.linear_term_per_km, l.constant_term});
  return layers;
}

// Everything the path tracer reads of the model, at full precision.
std::string model_key(const ref::AtmosphereModel& m) {
  json j{
      {"bottom_radius_km", m.bottom_radius_km},
      {"top_radius_km", m.top_radius_km},
      {"rayleigh_scattering", rgb(m.rayleigh_scattering)},
      {"rayleigh_density", profile(m.rayleigh_density)},
      {"mie_scattering", rgb(m.mie_scattering)},
      {"mie_extinction", rgb(m.mie_extinction)},
      {"mie_density", profile(m.mie_density)},
      {"mie_phase", m.mie_phase == ref::MiePhase::cornette_shanks ? "cornette_shanks" : "henyey_greenstein"},
      {"mie_g", m.mie_g},
      {"absorption_extinction", rgb(m.absorption_extinction)},
      {"absorption_density", profile(m.absorption_density)},
      {"ground_albedo", rgb(m.ground_albedo)}};
  return j.dump();
}

}  // namespace

std::vector<ref::ProbeGeometry> accuracy_rays() {
  std::vector<ref::ProbeGeometry> rays;
  for (double altitude : {0.0, 1.0, 10.0})
    for (double sun : {-6.0, 0.0, 3.0, 10.0, 30.0, 60.0, 90.0})
      for (double view : {2.0, 5.0, 10.0, 30.0, 60.0, 90.0})
        for (double azimuth : {0.0, 45.0, 90.0, 180.0}) {
          if ((sun == 90.0 || view == 90.0) && azimuth != 0.0) continue;
          rays.push_back({.altitude_km = altitude,
                          .view_zenith_deg = 90.0 - view,
                          .view_azimuth_deg = azimuth,
                          .sun_zenith_deg = 90.0 - sun,
                          .sun_azimuth_deg = 0.0});
        }
  // Appended, so that the quick tenth of the rays above stays what it was.
  for (double altitude : {0.0, 1.0, 10.0})
    for (double view : {2.0, 5.0, 10.0, 30.0, 60.0, 90.0})
      for (double azimuth : {0.0, 45.0, 90.0, 180.0}) {
        if (view == 90.0 && azimuth != 0.0) continue;
        rays.push_back({.altitude_km = altitude,
                        .view_zenith_deg = 90.0 - view,
                        .view_azimuth_deg = azimuth,
                        .sun_zenith_deg = 93.0,
                        .sun_azimuth_deg = 0.0});
      }
  for (double view : {2.0, 10.0, 30.0, 90.0})
    for (double azimuth : {0.0, 90.0, 180.0}) {
      if (view == 90.0 && azimuth != 0.0) continue;
      rays.push_back({.altitude_km = 0.0,
                      .view_zenith_deg = 90.0 - view,
                      .view_azimuth_deg = azimuth,
                      .sun_zenith_deg = 102.0,
                      .sun_azimuth_deg = 0.0});
    }
  return rays;
}

ReferenceCache::ReferenceCache(const ref::AtmosphereModel& model, const ReferenceSettings& settings)
    : model_key_(model_key(model)), settings_(settings) {}

std::size_t ReferenceCache::load(const std::string& path) {
  json j;
  try {
    j = parse_json_text(read_file_text(path, kMaxJsonBytes), path);
    if (j.at("format").get<int>() != 1 || j.at("model").dump() != json::parse(model_key_).dump() ||
        j.at("seed").get<std::uint64_t>() != settings_.seed ||
        j.at("chunk_size").get<std::uint64_t>() != settings_.chunk_size)
      return 0;
    // Each entry records its own sample count; files from before that carry one for all.
    const std::uint64_t file_samples = j.at("samples").get<std::uint64_t>();
    std::size_t n = 0;
    for (const json& r : j.at("rays")) {
      const ref::ProbeGeometry g{.altitude_km = r.at("altitude_km").get<double>(),
                                 .view_zenith_deg = r.at("view_zenith_deg").get<double>(),
                                 .view_azimuth_deg = r.at("view_azimuth_deg").get<double>(),
                                 .sun_zenith_deg = r.at("sun_zenith_deg").get<double>(),
                                 .sun_azimuth_deg = r.at("sun_azimuth_deg").get<double>()};
      if (r.value("samples", file_samples) != settings_.samples_for(g)) continue;
      put(g, {.radiance = rgb(r.at("radiance")), .ci95 = rgb(r.at("ci95"))});
      ++n;
    }
    return n;
  } catch (const json::exception&) {
    return 0;  // a damaged cache is recomputed, never trusted
  } catch (const Error&) {
    return 0;  // missing, not a regular file, over the bounds: recomputed too
  }
}

void ReferenceCache::save(const std::string& path) const {
  json rays = json::array();
  for (const auto& [k, e] : entries_) {
    const auto& [g, v] = e;
    rays.push_back({{"altitude_km", g.altitude_km},
                    {"view_zenith_deg", g.view_zenith_deg},
                    {"view_azimuth_deg", g.view_azimuth_deg},
                    {"sun_zenith_deg", g.sun_zenith_deg},
                    {"sun_azimuth_deg", g.sun_azimuth_deg},
                    {"samples", settings_.samples_for(g)},
                    {"radiance", rgb(v.radiance)},
                    {"ci95", rgb(v.ci95)}});
  }
  const json j{
      {"format", 1},
      {"what",
       "Path-traced all-orders radiance (1/sr, sun illuminance 1, the lit ground seen where a ray meets "
       "it) of welkin accuracy's rays; ci95 is the 95% confidence half-width"},
      {"model", json::parse(model_key_)},
      {"samples", settings_.samples},
      {"samples_sun_below_horizon", settings_.samples_sun_below_horizon},
      {"samples_deep_twilight", settings_.samples_deep_twilight},
      {"seed", settings_.seed},
      {"chunk_size", settings_.chunk_size},
      {"rays", rays}};
  write_file_atomically(path, j.dump(1) + "\n");
}

std::optional<CachedReference> ReferenceCache::find(const ref::ProbeGeometry& g) const {
  auto it = entries_.find(key(g));
  if (it == entries_.end()) return std::nullopt;
  return it->second.second;
}

void ReferenceCache::put(const ref::ProbeGeometry& g, const CachedReference& value) {
  entries_[key(g)] = {g, value};
}

CachedReference path_trace_reference(const ref::AtmosphereModel& model, const ref::ProbeGeometry& g,
                                     const ReferenceSettings& settings, int threads) {
  const ref::PathTraceSettings s{.samples = settings.samples_for(g),
                                 .seed = settings.seed,
                                 .threads = threads,
                                 .chunk_size = settings.chunk_size,
                                 .camera_sees_ground = true};
  const ref::ProbeResult p = ref::probe_path_traced(model, g, s);
  return {.radiance = {p.radiance[0], p.radiance[1], p.radiance[2]},
          .ci95 = {p.radiance_ci95[0], p.radiance_ci95[1], p.radiance_ci95[2]}};
}

}  // namespace welkin::atmosphere
