#pragma once
// The atmosphere's light term (registered in src/register.cpp): sun and moon through the
// transmittance LUT and the planet's shadow, sky light from the sky's irradiance, and aerial
// perspective for materials that write no depth. Opaque geometry gets aerial perspective from the
// atmosphere's deferred pass over the depth buffer instead, so it is applied exactly once.
#include "atmosphere/aerial_perspective.glsl"

vec3 atmosphere_term_aerial_perspective(vec3 camera_relative_m, out vec3 transmittance) {
  AtmosphereAerialPerspective ap = atmosphere_aerial_perspective(camera_relative_m);
  transmittance = ap.transmittance;
  return ap.inscattering;
}

// Sunlight or moonlight of unit irradiance scattered back along the camera's ray at a camera-relative
// point (Rayleigh and Mie, 1/(m sr)), and the air's extinction (1/m): the medium that volumetric
// shadowing integrates. The coefficients are per km in the block.
vec3 atmosphere_term_medium(vec3 camera_relative_m, vec3 view_dir, int light, out vec3 extinction) {
  AtmParams P = atm_params();
  float r = max(length(atmosphere_point_km(camera_relative_m)), P.bottom + P.lift);
  AtmMedium med = atm_medium(P, r - P.bottom);
  extinction = med.extinction * 1e-3;
  float c = dot(view_dir, light == 0 ? atm.sun_direction : atm.moon_direction);
  return (med.rayleigh * atm_rayleigh_phase(c) + med.mie * atm_mie_phase(c)) * 1e-3;
}
