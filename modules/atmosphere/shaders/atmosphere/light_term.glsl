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
