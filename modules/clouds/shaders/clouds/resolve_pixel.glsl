#pragma once
// Temporal upscaling of the clouds (one body for resolve.frag and resolve.comp): this frame marched
// one pixel of each N x N block (u_current, N = 2 or 4); the others come from the previous frame's
// result, reprojected through the clouds' own distance, and clipped to the range of this frame's
// neighbouring samples so that what moved or appeared does not leave ghosts. CLOUDS_CLIP 0 keeps
// plain reprojection (for the ghosting comparison of `welkin accuracy clouds`). Where the ray starts
// inside a cloud (the camera in it) nothing is reprojected: the history there would smear the cloud
// around the camera. CLOUDS_SILHOUETTES: the pixels next to the last frame's silhouettes were marched
// too this frame (silhouettes_mark.glsl), and are taken as marched.
// Besides the colour, each pixel's history keeps the scene's depth it was marched against
// (u_history_depth): in a held view it is reprojected only where that depth held (no geometry moved
// in front of the clouds or away).
// CLOUDS_WITH_CLUSTERS: the mesh clusters, drawn at this resolution or below, are also laid behind the result
// in a second target (march + T x clusters) for the composite, which then reads one texture at the
// frame's resolution instead of two; the history stays the march alone.
#include "clouds/reproject.glsl"
#if CLOUDS_WITH_CLUSTERS
#include "clouds/b_spline.glsl"
layout(binding = 3) uniform sampler2D u_clusters;  // premultiplied, opacity in alpha
#endif
layout(binding = 0) uniform sampler2D u_current;           // one pixel per block: colour, transmittance
// one pixel per block: the clouds' mean distance, where they turn opaque, up to where none (m)
layout(binding = 1) uniform sampler2D u_current_distance;
layout(binding = 2) uniform sampler2D u_history;           // the last result at the march resolution
#if CLOUDS_SILHOUETTES
// The pixels next to a silhouette marched again this frame (march_silhouettes.comp); -1 elsewhere.
layout(binding = 4) uniform sampler2D u_silhouettes;
#endif
uniform int u_block;               // N
uniform ivec2 u_offset;            // the position in the block marched this frame
uniform int u_history_valid;
uniform int u_full_frame;  // every pixel was marched this frame (no history yet): taken as it is
uniform float u_inside_cloud_m;  // a first cloud sample closer than this: the camera is in the cloud
// What the march reads (the view, the field, the light) held since the last frame: the fresh samples
// differ from their history by the march's jitter alone (where the scene's depth held too), and the
// history is kept unclipped.
uniform int u_view_held;
layout(binding = 5) uniform sampler2D u_scene_depth;    // this frame's (reversed Z; 0 = nothing), as marched
layout(binding = 6) uniform sampler2D u_history_depth;  // what the history's pixels were marched against

// The history at uv through a Catmull-Rom filter: a moving view reads it between texels every frame,
// and bilinear reads, repeated, blur the history (its silhouettes most) frame after frame. Nine
// bilinear reads: the two middle taps of each axis merged into one read between them (their weights
// have the same sign).
vec4 history_catmull_rom(vec2 uv) {
  vec2 size = vec2(textureSize(u_history, 0));
  vec2 texel = uv * size - 0.5;
  vec2 base = floor(texel), f = texel - base;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f)), w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f)), w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 p0 = (base - 0.5) / size, p12 = (base + 0.5 + w2 / w12) / size, p3 = (base + 2.5) / size;
  vec2 px[3] = vec2[3](p0, p12, p3), wx[3] = vec2[3](w0, w12, w3);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) sum += wx[i].x * wx[j].y * textureLod(u_history, vec2(px[i].x, px[j].y), 0.0);
  return sum;
}

// The resolved pixel (at the march's resolution; ndc its centre), and the scene's depth it stands for:
// this frame's where it is made of this frame's samples, else its history's.
vec4 resolved(ivec2 pixel, vec2 ndc, out float marched_depth) {
  marched_depth = textureLod(u_scene_depth, ndc * 0.5 + 0.5, 0.0).r;  // where the march reads it
  ivec2 block = pixel / u_block;
  ivec2 current_size = textureSize(u_current, 0);
  if (u_full_frame == 1) return texelFetch(u_current, pixel, 0);
  if (all(equal(pixel % u_block, u_offset))) return texelFetch(u_current, block, 0);
#if CLOUDS_SILHOUETTES
  vec4 marched = texelFetch(u_silhouettes, pixel, 0);
  if (marched.a >= 0.0) return marched;
#endif
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
  vec2 uv = previous_uv(ndc, distance_m);
  if (!in_view(uv)) return upsampled;
  // In a held view each pixel's history stands for the scene's depth it was marched against. Where
  // that changed (geometry moved in front of the clouds or away) the history is another scene's, and
  // the fresh samples around are taken instead, as where it was out of view: clipped to their range it
  // could stay (a hole where a ball stood against broken clouds, with clear sky among the samples).
  // Depth to 0.1% of the distance (reversed Z): the same drawing's.
  if (u_view_held == 1) {
    float then = texelFetch(u_history_depth, pixel, 0).r;
    if (abs(marched_depth - then) > 1e-3 * max(marched_depth, then)) return upsampled;
    marched_depth = then;
  }
#if CLOUDS_CLIP
  // How much the clouds changed since the history was written, seen at the four fresh samples
  // around the pixel (what a bilinear read between them weighs): each against the history where it
  // was last frame, moved in the image as this pixel moved.
  vec4 change = vec4(0.0);
  vec2 frame_size = vec2(textureSize(u_history, 0)), motion = uv - (ndc * 0.5 + 0.5);
  ivec2 corner = ivec2(floor(fresh_pos));
  for (int y = 0; y <= 1; ++y)
    for (int x = 0; x <= 1; ++x) {
      ivec2 q = clamp(corner + ivec2(x, y), ivec2(0), current_size - 1);
      vec2 q_uv = (vec2(q * u_block + u_offset) + 0.5) / frame_size + motion;
      change = in_view(q_uv) ? max(change, abs(texelFetch(u_current, q, 0) - texture(u_history, q_uv)))
                             : vec4(1e30);
    }
#endif
  // Where the camera did not move, the pixel lands on its own texel's centre up to rounding: that
  // texel is read as it is, or the history would be filtered again every frame and blur.
  vec2 texel = uv * vec2(textureSize(u_history, 0)) - 0.5;
  vec2 centre = round(texel);
  vec4 history = all(lessThan(abs(texel - centre), vec2(0.125)))
                     ? texelFetch(u_history, ivec2(centre), 0)
                     : history_catmull_rom(uv);
  history = max(history, vec4(0.0));  // the filter's negative lobes, at an edge
  history.a = min(history.a, 1.0);
#if CLOUDS_CLIP
  // Where the neighbours' history still holds (what changed is small against the neighbourhood's
  // range) this pixel's history is kept as it is: the range of the fresh samples around it would
  // clip away its own detail between them (a silhouette's pixels between samples on either side).
  // Where the clouds changed or moved in the image, the history is clipped to the range.
  // In a held view nothing changed but the jitter, which moves a thin lit edge's sample by all of its
  // value: read as change, it clipped the history toward the sparse samples around it frame after
  // frame, and the kept view lost its brightest small features (the peer scene at `low`, 4 x 4
  // blocks, 96x54: over 16 frames 83% of the same march's mean without the upscaling, 97% unclipped;
  // docs/clouds-light.md, "The peer scene's image").
  vec4 range = max(hi - lo, vec4(1e-6));
  float changed =
      max(max(change.r / range.r, change.g / range.g), max(change.b / range.b, change.a / range.a));
  if (u_view_held == 0) history = mix(history, clamp(history, lo, hi), smoothstep(0.1, 0.4, changed));
#endif
  return history;
}

#if CLOUDS_CLEAR
// Up to where this pixel's ray met no cloud (m; src/first_hit_skip.h), for the next frame's march: the
// march's own where it marched this pixel, else the least of the fresh samples around it.
float resolved_clear(ivec2 pixel) {
  ivec2 block = pixel / u_block;
  if (u_full_frame == 1) return texelFetch(u_current_distance, pixel, 0).b;
  if (all(equal(pixel % u_block, u_offset))) return texelFetch(u_current_distance, block, 0).b;
  ivec2 current_size = textureSize(u_current_distance, 0);
  float clear = 3.4e38;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x)
      clear = min(clear, texelFetch(u_current_distance,
                                    clamp(block + ivec2(x, y), ivec2(0), current_size - 1), 0).b);
  return clear;
}
#endif

#if CLOUDS_WITH_CLUSTERS
// The clusters laid behind the resolved clouds: march + T x clusters. Drawn at a lower resolution
// than the march's, they are magnified through a B-spline here, at the march's pixels: four reads
// at a quarter of the frame's pixels, where the composite would read them at every pixel.
vec4 with_clusters(ivec2 pixel, vec4 clouds) {
  ivec2 size = textureSize(u_history, 0);
  vec4 c = textureSize(u_clusters, 0) == size ? texelFetch(u_clusters, pixel, 0)
                                              : clouds_b_spline(u_clusters, (vec2(pixel) + 0.5) / vec2(size));
  return vec4(clouds.rgb + clouds.a * c.rgb, clouds.a * (1.0 - c.a));
}
#endif
