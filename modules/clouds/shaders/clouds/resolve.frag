// Temporal upscaling of the clouds: this frame marched one pixel of each N x N block (u_current,
// N = 2 or 4); the others come from the previous frame's result, reprojected
// through the clouds' own distance, and clipped to the range of this frame's neighbouring samples
// so that what moved or appeared does not leave ghosts. CLOUDS_CLIP 0 keeps plain reprojection
// (for the ghosting comparison of `welkin accuracy clouds`). Where the ray starts inside a cloud (the
// camera in it) nothing is reprojected: the history there would smear the cloud around the camera.
// CLOUDS_WITH_CLUSTERS: the mesh clusters, drawn at this resolution, are also laid behind the result
// in a second target (march + T x clusters) for the composite, which then reads one texture at the
// frame's resolution instead of two; the history stays the march alone.
#include "welkin/view.glsl"
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
#if CLOUDS_WITH_CLUSTERS
layout(location = 1) out vec4 o_with_clusters;
layout(binding = 3) uniform sampler2D u_clusters;  // premultiplied, opacity in alpha
#endif
layout(binding = 0) uniform sampler2D u_current;           // one pixel per block: colour, transmittance
layout(binding = 1) uniform sampler2D u_current_distance;  // one pixel per block: mean and first cloud distance (m)
layout(binding = 2) uniform sampler2D u_history;           // the last result at the march resolution
uniform int u_block;               // N
uniform ivec2 u_offset;            // the position in the block marched this frame
uniform mat4 u_inverse_view_projection;
uniform mat4 u_previous_view_projection;
uniform vec3 u_camera_moved_m;     // this frame's camera minus the last one's
uniform int u_history_valid;
uniform int u_full_frame;  // every pixel was marched this frame (no history yet): taken as it is
uniform float u_inside_cloud_m;  // a first cloud sample closer than this: the camera is in the cloud

vec4 resolved(ivec2 pixel) {
  ivec2 block = pixel / u_block;
  ivec2 current_size = textureSize(u_current, 0);
  if (u_full_frame == 1) return texelFetch(u_current, pixel, 0);
  if (all(equal(pixel % u_block, u_offset))) return texelFetch(u_current, block, 0);
  // The neighbourhood of fresh samples around this pixel: its range bounds the history.
  vec4 lo = vec4(1e30), hi = vec4(-1e30), nearest = vec4(0.0);
  float distance_m = 0.0, front_m = 0.0;
  vec2 fresh_pos = vec2(pixel - u_offset) / float(u_block);  // in u_current's texels (centres at integers)
  float best = 1e30;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(block + ivec2(x, y), ivec2(0), current_size - 1);
      vec4 c = texelFetch(u_current, q, 0);
      lo = min(lo, c), hi = max(hi, c);
      float d = dot(vec2(q) - fresh_pos, vec2(q) - fresh_pos);
      if (d < best) {
        vec2 distances = texelFetch(u_current_distance, q, 0).rg;
        best = d, nearest = c, distance_m = distances.x, front_m = distances.y;
      }
    }
  vec4 upsampled = texture(u_current, (fresh_pos + 0.5) / vec2(current_size));
  if (u_history_valid == 0 || front_m < u_inside_cloud_m) return upsampled;
  // Where this pixel's clouds were last frame, seen from last frame's camera.
  vec3 dir = view_ray_direction(u_inverse_view_projection, v_ndc);
  vec4 clip = u_previous_view_projection * vec4(dir * distance_m + u_camera_moved_m, 1.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return upsampled;
  // Where the camera did not move, the pixel lands on its own texel's centre up to rounding: that
  // texel is read as it is, or the history would be filtered again every frame and blur.
  vec2 texel = uv * vec2(textureSize(u_history, 0)) - 0.5;
  vec2 centre = round(texel);
  vec4 history = all(lessThan(abs(texel - centre), vec2(0.125)))
                     ? texelFetch(u_history, ivec2(centre), 0)
                     : texture(u_history, uv);
#if CLOUDS_CLIP
  history = clamp(history, lo, hi);
#endif
  return history;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  o_color = resolved(pixel);
#if CLOUDS_WITH_CLUSTERS
  vec4 c = texelFetch(u_clusters, pixel, 0);
  o_with_clusters = vec4(o_color.rgb + o_color.a * c.rgb, o_color.a * (1.0 - c.a));
#endif
}
