#pragma once
// The atmosphere's replacement for the runtime's material lights (same functions, same callers):
// sun and moon through the transmittance LUT and the planet's shadow, sky light from the sky's
// irradiance. Aerial perspective is left to the atmosphere's deferred pass (these materials write
// depth), so it is applied exactly once.
#include "atmosphere/aerial_perspective.glsl"

vec3 welkin_sun_direction() { return atmosphere_sun_direction(); }
vec3 welkin_sun_irradiance(vec3 camera_relative_m) { return atmosphere_sun_irradiance(camera_relative_m); }
vec3 welkin_moon_direction() { return atmosphere_moon_direction(); }
vec3 welkin_moon_irradiance(vec3 camera_relative_m) { return atmosphere_moon_irradiance(camera_relative_m); }
vec3 welkin_sky_irradiance(vec3 normal) { return atmosphere_sky_irradiance(normal); }
