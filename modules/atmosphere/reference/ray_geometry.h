// Rays in a planet-centred frame, described Bruneton-style by the radius r of their origin and the
// cosine mu of their zenith angle there; s is the distance along the ray. Formulas avoid the
// cancellations that lose altitude precision on large planets and for grazing rays.
#pragma once

#include <glm/vec3.hpp>
#include <vector>

#include "reference/atmosphere_model.h"

namespace welkin::atmosphere::reference {

// The part of a ray that lies in the atmosphere and is visible from its origin.
struct RayInterval {
  double start_km = 0.0;     // 0 inside the atmosphere, the entry distance from space.
  double end_km = 0.0;       // Ground hit or exit through the top.
  bool intersects = false;   // False when a ray from space misses the atmosphere.
  bool hits_ground = false;  // The ray ends on the ground, not at the top.
};

// Origin radius clamped to the ground: a camera under the ground sees from the surface.
double clamp_to_ground(const AtmosphereModel& model, double r_km);

// Visible atmospheric interval of the ray (origin radius clamped to the ground first).
RayInterval atmosphere_interval(const AtmosphereModel& model, double r_km, double mu);

// Rays that pass within a relative kTangentTolerance (in squared radius) of tangency count as
// missing the sphere. This settles rays that graze the planet to rounding consistently, e.g. a
// view ray lying on the surface of the planet's shadow (camera on the terminator looking away
// from a sun exactly on the horizon), which would otherwise flicker between lit and dark.
inline constexpr double kTangentTolerance = 1e-12;

// True when the ray from radius r (>= bottom) with zenith cosine mu meets the sphere of radius
// bottom_radius_km (tangent rays, within kTangentTolerance, do not: they reach the top).
bool ray_hits_sphere_below(double bottom_radius_km, double r_km, double mu);

// Radius at distance s along the ray, written as a sum of non-negative terms.
double radius_along_ray(double r_km, double mu, double s_km);
// Altitude above bottom_radius_km at distance s, without the cancellation of radius - bottom.
double altitude_along_ray(double bottom_radius_km, double r_km, double mu, double s_km);

// Sorted split points in [s0, s1] (ends included): where the ray crosses an altitude at which a
// density profile has a kink, and the ray's lowest point, where grazing rays peak.
std::vector<double> ray_breakpoints(const AtmosphereModel& model, double r_km, double mu,
                                    double s0_km, double s1_km);

// Radius and zenith cosine of a planet-centred position and a unit direction.
struct RadiusMu {
  double r_km;
  double mu;
};
RadiusMu radius_mu(const glm::dvec3& position_km, const glm::dvec3& direction);

}  // namespace welkin::atmosphere::reference
