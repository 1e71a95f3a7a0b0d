#pragma once
// The view ray of a pixel and where it ends, shared by the shafts and their application.
#include "welkin/view.glsl"
#include "godrays/blocks.glsl.h"

// The frame's block (src/frame_block.h: kFrameBlockBinding).
layout(std140, binding = 0) uniform GodRaysFrame { GodRaysFrameGpu gr; };

// Distance along a ray from the camera to the planet's surface (the atmosphere draws the ground
// without depth), or infinity where the ray misses it. |o|^2 - R^2 = h (2R + h), exact in float.
float ground_distance_m(vec3 dir) {
  float b = (gr.planet_radius_m + gr.camera_altitude_m) * dot(gr.up, dir);
  float c = gr.camera_altitude_m * (2.0 * gr.planet_radius_m + gr.camera_altitude_m);
  float disc = b * b - c;
  if (b >= 0.0 || disc < 0.0) return 3.4e38;
  return c / (-b + sqrt(disc));  // the nearer root, without cancellation
}

// Distance along the ray of the pixel at `texel` of the depth buffer to the geometry, else to the
// planet's surface, else infinity (reversed Z: 0 is nothing).
float scene_distance_m(sampler2D depth_buffer, ivec2 texel, vec2 ndc) {
  float depth = texelFetch(depth_buffer, texel, 0).r;
  if (depth <= 0.0) return ground_distance_m(view_ray_direction(gr.inverse_view_projection, ndc));
  vec4 p = gr.inverse_view_projection * vec4(ndc, depth, 1.0);
  return length(p.xyz / p.w);
}

