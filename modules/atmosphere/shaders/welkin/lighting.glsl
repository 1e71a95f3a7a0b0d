#pragma once
// The atmosphere's replacement for the runtime's material lighting (same function, same callers):
// sun and moon through the transmittance LUT and the planet's shadow, sky light from the sky's
// spherical harmonics. Aerial perspective is left to the atmosphere's deferred pass (these
// materials write depth), so it is applied exactly once.
#include "atmosphere/aerial_perspective.glsl"

vec3 shade_lambert(vec3 albedo, vec3 normal, vec3 camera_relative_position) {
  vec3 p = camera_relative_position;
  vec3 e = atmosphere_sun_irradiance(p) * max(dot(normal, atmosphere_sun_direction()), 0.0) +
           atmosphere_moon_irradiance(p) * max(dot(normal, atmosphere_moon_direction()), 0.0) +
           atmosphere_sky_irradiance(normal);
  return albedo / ATM_PI * e;
}
