#pragma once
// Material lighting for the built-in shapes: a Lambert sun plus a constant sky term. The atmosphere
// module provides a physically based replacement (sun through the transmittance LUT, sky
// irradiance, aerial perspective) that every material reaches through the same functions.
uniform vec3 u_sun_direction;
uniform vec3 u_sun_illuminance;
uniform float u_ambient_fraction;

vec3 shade_lambert(vec3 albedo, vec3 normal, vec3 camera_relative_position) {
  float n_dot_l = max(dot(normal, u_sun_direction), 0.0);
  vec3 sky = u_sun_illuminance * u_ambient_fraction * (0.5 + 0.5 * normal.z);
  return albedo / 3.14159265 * (u_sun_illuminance * n_dot_l + sky);
}
