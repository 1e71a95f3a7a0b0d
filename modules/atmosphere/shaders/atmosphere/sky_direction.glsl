#pragma once
// The view ray through a point of the screen, for the sky (sky.vert's corners, sky.comp's pixels): not
// normalised, in world axes, or in the sky-view LUT's frame where sky_pixel fetches the LUT alone (it
// saves a matrix per pixel; the ground's light and the discs need world axes). The inverse projection
// of a constant depth is affine in screen space, so interpolating it between corners is exact.
#include "atmosphere/common.glsl"

vec3 sky_direction(vec2 ndc) {
  vec4 far_point = atm.inverse_view_projection * vec4(ndc, 0.5, 1.0);
  vec3 dir = far_point.xyz / far_point.w;
#if ATM_SKY_MODE == 0 && !ATM_SKY_DISCS && !ATM_SKY_GROUND_LIGHT
  dir = transpose(mat3(atm.sky_frame)) * dir;
#endif
  return dir;
}
