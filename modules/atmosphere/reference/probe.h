// The geometry `welkin probe` evaluates: one camera, one view ray, one sun, in the camera's local
// frame (z up along the planet normal, azimuths measured from x towards y in the same frame).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>

#include "reference/atmosphere_model.h"
#include "reference/path_tracer.h"

namespace welkin::atmosphere::reference {

// One probe: camera altitude and the view and sun directions as zenith / azimuth angles.
struct ProbeGeometry {
  double altitude_km = 0.0;  // Above the ground; negative values are clamped to the ground.
  double view_zenith_deg = 0.0;
  double view_azimuth_deg = 0.0;
  double sun_zenith_deg = 0.0;
  double sun_azimuth_deg = 0.0;
};

// What `welkin probe` prints for one technique.
struct ProbeResult {
  double transmittance[3] = {1.0, 1.0, 1.0};  // View ray to its end (ground or top).
  double radiance[3] = {0.0, 0.0, 0.0};       // 1/sr for sun illuminance 1.
  // Path tracing: 95% confidence half-width. Quadrature: the quadrature's error estimate.
  double radiance_ci95[3] = {0.0, 0.0, 0.0};
  std::uint64_t samples = 0;  // Paths traced; 0 for quadrature.
  double wall_ms = 0.0;
};

// Planet-centred camera position and unit view and sun directions of a probe; the camera sits on
// the +z axis so the local frame is the global one.
struct ProbeRay {
  glm::dvec3 camera_km;
  glm::dvec3 view_dir;
  glm::dvec3 sun_dir;
};
// The probe's ray in that frame, the camera clamped to the ground.
ProbeRay probe_ray(const AtmosphereModel& model, const ProbeGeometry& geometry);

// Transmittance and single-scattering radiance by quadrature (single_scattering.h).
ProbeResult probe_quadrature(const AtmosphereModel& model, const ProbeGeometry& geometry);

// The same transmittance, and radiance of all orders (up to settings.max_order) by path tracing.
ProbeResult probe_path_traced(const AtmosphereModel& model, const ProbeGeometry& geometry,
                              const PathTraceSettings& settings = {});

}  // namespace welkin::atmosphere::reference
