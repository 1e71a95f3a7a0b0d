#pragma once
// The runtime's own light term: one directional light (the scene's first core.DirectionalLight, or
// its defaults) and a sky brighter overhead than at the horizon. Serves scenes without an
// atmosphere; a module that models light transport provides the lights instead.
#include "welkin/default_lights_block.glsl.h"
layout(std140, binding = WELKIN_BLOCK_CORE_DEFAULT_LIGHTS) uniform WelkinDefaultLights {
  WelkinDefaultLightsGpu default_lights;
};

vec3 default_sun_direction() { return default_lights.direction; }
vec3 default_sun_irradiance(vec3 camera_relative_m) { return default_lights.illuminance_lux; }
vec3 default_moon_direction() { return vec3(0.0, 0.0, 1.0); }
vec3 default_moon_irradiance(vec3 camera_relative_m) { return vec3(0.0); }
vec3 default_sky_irradiance(vec3 normal) {
  return default_lights.illuminance_lux * default_lights.sky_fraction * (0.5 + 0.5 * normal.z);
}
