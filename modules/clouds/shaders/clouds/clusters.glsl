#pragma once
// The mesh clusters' puffs (src/clusters.cpp): ellipsoids whose extinction falls from sigma at the
// centre to zero at the surface as sigma (1 - q), q the squared normalised radius, so edges are soft
// without a fade. Along a ray, q is a parabola in the distance t, q = a (t - t_mid)^2 + q_min, and
// the optical depth of any stretch has a closed form; it is written about the chord's middle so that
// a puff 50 km away keeps its precision in float.

#include "clouds/puff_block.glsl.h"

// The clusters' axes (camera-relative): along the wind, across it, and up at the camera.
uniform vec3 u_axis_wind, u_axis_across, u_axis_up;

// A point and a direction in the puff's normalised frame (the ellipsoid becomes the unit sphere).
vec3 puff_local(vec3 x, vec3 centre, vec3 radii) {
  vec3 r = x - centre;
  return vec3(dot(r, u_axis_wind), dot(r, u_axis_across), dot(r, u_axis_up)) / radii;
}
vec3 puff_direction(vec3 d, vec3 radii) {
  return vec3(dot(d, u_axis_wind), dot(d, u_axis_across), dot(d, u_axis_up)) / radii;
}

// A ray po + t pd in the normalised frame against the unit sphere: (t_mid, a, q_min, half length of
// the chord); half length < 0: missed.
vec4 puff_chord_local(vec3 po, vec3 pd) {
  float a = max(dot(pd, pd), 1e-30);
  float t_mid = -dot(po, pd) / a;
  vec3 closest = po + pd * t_mid;
  float q_min = dot(closest, closest);
  float half_length = q_min < 1.0 ? sqrt((1.0 - q_min) / a) : -1.0;
  return vec4(t_mid, a, q_min, half_length);
}
vec4 puff_chord(vec3 o, vec3 d, vec3 centre, vec3 radii) {
  return puff_chord_local(puff_local(o, centre, radii), puff_direction(d, radii));
}

// The unit-extinction optical depth from the chord's middle to s (|s| <= half length): an
// antiderivative of 1 - q_min - a s^2.
float puff_depth_at(vec4 chord, float s) { return (1.0 - chord.z) * s - chord.y * s * s * s / 3.0; }

// Unit-extinction optical depth of the stretch [t0, t1] of the ray (clipped to the puff).
float puff_optical_depth(vec4 chord, float t0, float t1) {
  if (chord.w <= 0.0) return 0.0;
  float s0 = clamp(t0 - chord.x, -chord.w, chord.w), s1 = clamp(t1 - chord.x, -chord.w, chord.w);
  return max(puff_depth_at(chord, s1) - puff_depth_at(chord, s0), 0.0);
}

// The s in [s0, s1] where the unit-extinction depth from s0 reaches `depth` (a monotone cubic):
// a linear first guess, then Newton steps kept inside the stretch.
float puff_invert_depth(vec4 chord, float s0, float s1, float depth) {
  float f0 = puff_depth_at(chord, s0), total = puff_depth_at(chord, s1) - f0;
  float s = s0 + (s1 - s0) * clamp(depth / max(total, 1e-30), 0.0, 1.0);
  for (int i = 0; i < 3; ++i) {
    float slope = max(1.0 - chord.z - chord.y * s * s, 1e-6);
    s = clamp(s - (puff_depth_at(chord, s) - f0 - depth) / slope, s0, s1);
  }
  return s;
}
