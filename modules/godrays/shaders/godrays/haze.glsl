#pragma once
// Haze: an exponential layer of aerosol over the ground (takram's sparse fog). The layer is taken as
// flat along a ray (its altitude h0 + mu t): exact within the few kilometres where it is dense.
#include "godrays/view_ray.glsl"

uniform vec4 u_haze;      // x: density at the ground (1/m), y: 1 / scale height (1/m), z, w: scattering and
                          // absorption per density
uniform float u_haze_g;   // Henyey-Greenstein asymmetry

float haze_extinction_per_density() { return u_haze.z + u_haze.w; }

float haze_density(vec3 p) {
  float altitude = u_planet.y + dot(p, u_up);
  return u_haze.x * exp(-max(altitude, 0.0) * u_haze.y);
}

float haze_phase(float c) {
  float g = u_haze_g, base = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * 3.14159265358979 * base * sqrt(max(base, 1e-12)));
}

// Optical depth of the haze from the camera to distance t along dir (t may be infinite): the density
// at the camera and at the end as exponentials of their altitudes (never of their difference, which
// overflows where the camera is high above the layer), with the level ray's limit.
float haze_optical_depth(vec3 dir, float t) {
  t = min(t, 1e8);
  float k = u_haze.y, mu = dot(dir, u_up), h0 = max(u_planet.y, 0.0);
  // the layer is flat along the ray: a ray to the ground ends a little below it
  float h1 = max(h0 + mu * t, -1000.0);
  float sigma = u_haze.x * haze_extinction_per_density();
  if (abs(mu * k * t) < 1e-4) return sigma * exp(-h0 * k) * t * (1.0 - 0.5 * mu * k * t);
  return sigma * (exp(-h0 * k) - exp(-h1 * k)) / (k * mu);
}
