#pragma once
// The view ray of a pixel and where it ends, shared by the shafts and their application.
#include "welkin/view.glsl"

uniform mat4 u_inverse_view_projection;
uniform float u_max_distance_m;  // the air beyond is taken as lit
uniform vec3 u_up;               // at the camera, from the planet's centre
uniform vec2 u_planet;           // x: the planet's radius, y: the camera's altitude above it (m)

// Distance along a ray from the camera to the planet's surface (the atmosphere draws the ground
// without depth), or infinity where the ray misses it. |o|^2 - R^2 = h (2R + h), exact in float.
float ground_distance_m(vec3 dir) {
  float b = (u_planet.x + u_planet.y) * dot(u_up, dir);
  float c = u_planet.y * (2.0 * u_planet.x + u_planet.y);
  float disc = b * b - c;
  if (b >= 0.0 || disc < 0.0) return 3.4e38;
  return c / (-b + sqrt(disc));  // the nearer root, without cancellation
}

// Distance along the ray of the pixel at `texel` of the depth buffer to the geometry, else to the
// planet's surface, else infinity (reversed Z: 0 is nothing).
float scene_distance_m(sampler2D depth_buffer, ivec2 texel, vec2 ndc) {
  float depth = texelFetch(depth_buffer, texel, 0).r;
  if (depth <= 0.0) return ground_distance_m(view_ray_direction(u_inverse_view_projection, ndc));
  vec4 p = u_inverse_view_projection * vec4(ndc, depth, 1.0);
  return length(p.xyz / p.w);
}

