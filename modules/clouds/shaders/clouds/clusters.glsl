#pragma once
// The mesh clusters' puffs (src/clusters.cpp): boxes, each a column of its cell through the layer,
// whose pixels march the layer's own field (clouds/puff.frag).

#include "clouds/puff_block.glsl.h"

// The clusters' axes (camera-relative): along the wind, across it, and up at the camera.
uniform vec3 u_axis_wind, u_axis_across, u_axis_up;

// A point and a direction in the puff's normalised frame (the box becomes [-1, 1]^3).
vec3 puff_local(vec3 x, vec3 centre, vec3 radii) {
  vec3 r = x - centre;
  return vec3(dot(r, u_axis_wind), dot(r, u_axis_across), dot(r, u_axis_up)) / radii;
}
vec3 puff_direction(vec3 d, vec3 radii) {
  return vec3(dot(d, u_axis_wind), dot(d, u_axis_across), dot(d, u_axis_up)) / radii;
}
