#pragma once
// Haze: an exponential layer of aerosol over the ground (takram's sparse fog). The layer is taken as
// flat along a ray (its altitude h0 + mu t): exact within the few kilometres where it is dense.
#include "godrays/view_ray.glsl"

float haze_extinction_per_density() { return gr.haze_scattering + gr.haze_absorption; }

float haze_density(vec3 p) {
  float altitude = gr.camera_altitude_m + dot(p, gr.up);
  return gr.haze_density_per_m * exp(-max(altitude, 0.0) * gr.haze_inverse_height_per_m);
}

float haze_phase(float c) {
  float g = gr.haze_g, base = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * 3.14159265358979 * base * sqrt(max(base, 1e-12)));
}

// Optical depth of the haze from the camera to distance t along dir (t may be infinite): the density
// at the camera and at the end as exponentials of their altitudes (never of their difference, which
// overflows where the camera is high above the layer), with the level ray's limit.
float haze_optical_depth(vec3 dir, float t) {
  t = min(t, 1e8);
  float k = gr.haze_inverse_height_per_m, mu = dot(dir, gr.up), h0 = max(gr.camera_altitude_m, 0.0);
  // the layer is flat along the ray: a ray to the ground ends a little below it
  float h1 = max(h0 + mu * t, -1000.0);
  float sigma = gr.haze_density_per_m * haze_extinction_per_density();
  if (abs(mu * k * t) < 1e-4) return sigma * exp(-h0 * k) * t * (1.0 - 0.5 * mu * k * t);
  return sigma * (exp(-h0 * k) - exp(-h1 * k)) / (k * mu);
}
