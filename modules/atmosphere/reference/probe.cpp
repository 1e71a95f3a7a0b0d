#include "reference/probe.h"

#include <chrono>
#include <cmath>

#include "reference/ray_geometry.h"
#include "reference/single_scattering.h"
#include "reference/transmittance.h"

namespace welkin::atmosphere::reference {

namespace {

glm::dvec3 direction(double zenith_deg, double azimuth_deg) {
  const double zenith = zenith_deg * kPi / 180.0;
  const double azimuth = azimuth_deg * kPi / 180.0;
  return {std::sin(zenith) * std::cos(azimuth), std::sin(zenith) * std::sin(azimuth),
          std::cos(zenith)};
}

void store(double out[3], const glm::dvec3& v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

ProbeRay probe_ray(const AtmosphereModel& model, const ProbeGeometry& geometry) {
  const double r = clamp_to_ground(model, model.bottom_radius_km + geometry.altitude_km);
  return {glm::dvec3(0.0, 0.0, r), direction(geometry.view_zenith_deg, geometry.view_azimuth_deg),
          direction(geometry.sun_zenith_deg, geometry.sun_azimuth_deg)};
}

ProbeResult probe_quadrature(const AtmosphereModel& model, const ProbeGeometry& geometry) {
  const auto start = std::chrono::steady_clock::now();
  const ProbeRay ray = probe_ray(model, geometry);
  const SingleScatteringResult ss =
      single_scattering(model, ray.camera_km, ray.view_dir, ray.sun_dir);
  ProbeResult result;
  store(result.transmittance, transmittance_to_boundary(model, ray.camera_km.z, ray.view_dir.z));
  store(result.radiance, ss.radiance);
  store(result.radiance_ci95, ss.error_estimate);
  result.wall_ms = elapsed_ms(start);
  return result;
}

ProbeResult probe_path_traced(const AtmosphereModel& model, const ProbeGeometry& geometry,
                              const PathTraceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const ProbeRay ray = probe_ray(model, geometry);
  const PathTraceResult pt = path_trace(model, ray.camera_km, ray.view_dir, ray.sun_dir, settings);
  ProbeResult result;
  store(result.transmittance, transmittance_to_boundary(model, ray.camera_km.z, ray.view_dir.z));
  store(result.radiance, pt.radiance);
  store(result.radiance_ci95, pt.ci95);
  result.samples = pt.samples;
  result.wall_ms = elapsed_ms(start);
  return result;
}

}  // namespace welkin::atmosphere::reference
