#pragma once
// The light a material receives, as functions every material calls: sun and moon (direction, and
// the illuminance arriving at a camera-relative point) and sky light on a surface. This default
// serves scenes without an atmosphere (a core.DirectionalLight, or a fixed light); a module that
// models light transport overrides the file (the atmosphere's version goes through its LUTs).
uniform vec3 u_sun_direction;
uniform vec3 u_sun_illuminance;
uniform float u_ambient_fraction;

vec3 welkin_sun_direction() { return u_sun_direction; }
vec3 welkin_sun_irradiance(vec3 camera_relative_m) { return u_sun_illuminance; }
vec3 welkin_moon_direction() { return vec3(0.0, 0.0, 1.0); }
vec3 welkin_moon_irradiance(vec3 camera_relative_m) { return vec3(0.0); }
// A sky brighter overhead than at the horizon, as a fraction of the sun.
vec3 welkin_sky_irradiance(vec3 normal) { return u_sun_illuminance * u_ambient_fraction * (0.5 + 0.5 * normal.z); }
