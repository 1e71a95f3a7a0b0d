#pragma once
// The volumetric clouds along each view ray, at the march resolution (one body for march.frag and
// march.comp): radiance that reaches the camera from the clouds and from the air in front of them
// (rgb), and the clouds' transmittance (a).
// The composite adds rgb and scales what lies behind by a. Light at every sample comes from the
// light environment: the sun or moon through the atmosphere's transmittance, the sky's irradiance.
//   CLOUDS_AP_MODE 0: aerial perspective along the ray (each sample's light is attenuated by the air
//                     in front of it, and the air in front of each opacity step is added; the air's
//                     terms are interpolated between the ends of each segment through the layers)
//                  1: once at the transmittance-weighted mean depth (takram's approximation, kept
//                     for comparison: it fails where distant sparse clouds overlap)
//                  2: once at the first cloud sample (the camera in space: the froxels cover no vacuum)
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "welkin/lighting.glsl"
#include "clouds/light_march.glsl"
#include "welkin/view.glsl"

// Temporal upscaling marches one pixel of each N x N block per frame: pixel p of the march's target
// stands for march pixel p * x + (y, z); without it, x = 1 and the offset is 0.
uniform ivec3 u_stride_offset;
layout(binding = 3) uniform sampler2D u_depth;       // the scene's depth (reversed Z; 0 = nothing)
layout(binding = 4) uniform sampler2D u_blue_noise;  // 64 x 64, void-and-cluster
#if CLOUDS_CLUSTER_FRONT
// Where the mesh clusters drawn before the march turn opaque (m, full resolution): the march ends
// there as at the scene's geometry.
layout(binding = CLOUDS_UNIT_CLUSTER_FRONT) uniform sampler2D u_cluster_front;
#endif

#if CLOUDS_SKIP
// The empty-space skipping from the last frame (src/first_hit_skip.h): where its rays met no cloud.
layout(binding = CLOUDS_UNIT_FIRST_HIT) uniform sampler2D u_first_hit;  // its view, the march's size (m)
uniform mat4 u_skip_previous_view_projection;
uniform vec3 u_skip_camera_moved_m;  // this frame's camera minus the last one's
uniform float u_skip_margin_m;       // how far the camera and the field moved since, at most
uniform int u_skip_round;            // the blocks with (x + 3 y + round) % 8 == 0 are marched whole

// Where this pixel's ray may start: a cloud at distance t along it lay, last frame, at least
// t - margin from that camera, along a ray that projects, for the points from the start on, within
// half a texel of the direction's own image (a move of the camera spreads them along a line): the
// 3 x 3 texels around hold the rays around all of them, and none met a cloud before its distance.
// One block in eight is marched whole each frame, in turn: every 3 x 3 blocks hold one (x + 3 y takes
// nine successive values there), whose distances the resolve's and the next march's neighbourhoods
// carry to the others.
float clouds_skip_start(ivec2 pixel, vec3 dir) {
  ivec2 block = pixel / u_stride_offset.x;
  if (((block.x + 3 * block.y + u_skip_round) & 7) == 0) return 0.0;
  ivec2 size = textureSize(u_first_hit, 0);
  vec4 far = u_skip_previous_view_projection * vec4(dir, 0.0);
  if (far.w <= 0.0) return 0.0;
  vec2 texel = (far.xy / far.w * 0.5 + 0.5) * vec2(size) - 0.5;
  ivec2 centre = ivec2(round(texel));
  // Rays at the last view's border had no neighbours beyond it: marched whole.
  if (any(lessThan(centre, ivec2(1))) || any(greaterThan(centre, size - 2))) return 0.0;
  float clear = 3.4e38;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) clear = min(clear, texelFetch(u_first_hit, centre + ivec2(x, y), 0).r);
  float start = clear - u_skip_margin_m;
  if (start <= 0.0) return 0.0;
  vec4 near = u_skip_previous_view_projection * vec4(dir * start + u_skip_camera_moved_m, 1.0);
  if (near.w <= 0.0) return 0.0;
  vec2 near_texel = (near.xy / near.w * 0.5 + 0.5) * vec2(size) - 0.5;
  return all(lessThanEqual(abs(near_texel - texel), vec2(0.5))) ? start : 0.0;
}
#endif

// Distance to the scene's geometry along this pixel's ray (infinite where there is none).
float scene_distance(vec2 ndc) {
  float depth = textureLod(u_depth, ndc * 0.5 + 0.5, 0.0).r;
  if (depth <= 0.0) return 3.4e38;
  vec4 p = cl.inverse_view_projection * vec4(ndc, depth, 1.0);
  return length(p.xyz / p.w);
}

struct Accumulated {
  vec3 color;           // light from the clouds (and, per sample, the air in front of them)
  float transmittance;  // of the clouds alone
  float depth_weight, weighted_depth;  // opacity-weighted mean distance (reprojection; CLOUDS_AP_MODE 1)
  float front;                         // distance where the clouds' transmittance first fell below 0.9
  bool ap_taken;                       // CLOUDS_AP_MODE 2: the air's terms at the first cloud
  vec3 ap_inscattering, ap_transmittance;
  int steps;
  float clear_m;  // up to here the ray met no cloud (its last empty sample before the first cloud)
};

// CLOUDS_BANDS (density_field.cpp's band_defines): the altitude bands, CLOUDS_BAND_LAYERS_i the layers
// band i's samples and their light steps can reach (0: one march with every layer for all of them).
#ifndef CLOUDS_BANDS
#define CLOUDS_BANDS 0
#endif

// The light reaching the clouds and the air in front of them change over kilometres, not metres:
// they are looked up at both ends of a stretch of the ray and interpolated along it. (A software
// rasteriser runs a lookup inside the loop for a whole group of pixels whenever any one of them needs
// it; and before the bands' marches, which it runs each for the whole group, once.)
struct SegmentEnds {
  vec3 up0, up1, e_light0, e_light1, e_sky0, e_sky1;
  vec3 ap_s0, ap_s1, ap_t0, ap_t1;  // CLOUDS_AP_MODE 0
  float system0, system1;
};
SegmentEnds segment_ends(vec3 dir, vec2 segment) {
  SegmentEnds e;
  vec3 x0 = dir * segment.x, x1 = dir * segment.y;
  e.up0 = normalize(cl.up * cl.camera_radius_m + x0), e.up1 = normalize(cl.up * cl.camera_radius_m + x1);
  e.e_light0 = cl.moon_marched > 0.5 ? welkin_moon_irradiance(x0) : welkin_sun_irradiance(x0);
  e.e_light1 = cl.moon_marched > 0.5 ? welkin_moon_irradiance(x1) : welkin_sun_irradiance(x1);
  e.e_sky0 = welkin_sky_irradiance(e.up0), e.e_sky1 = welkin_sky_irradiance(e.up1);
#if CLOUDS_AP_MODE == 0
  e.ap_s0 = welkin_aerial_perspective(x0, e.ap_t0), e.ap_s1 = welkin_aerial_perspective(x1, e.ap_t1);
#endif
  e.system0 = clouds_weather_system_at(x0), e.system1 = clouds_weather_system_at(x1);
  return e;
}

// The march through one stretch of the ray from `start` on (the light and the air interpolated
// between the stretch's ends `e` whatever the start), with the compiled layers in `layers` (density.glsl).
void march_segment(int layers, vec3 dir, vec2 segment, SegmentEnds e, float start, float jitter,
                   inout Accumulated acc) {
  bool detail = true;  // for the layers that use it (density.glsl)
  vec3 l = cl.moon_marched > 0.5 ? welkin_moon_direction() : welkin_sun_direction();
  float mu = dot(dir, l);
  float extinction_per_density = cl.scattering + cl.absorption;
  float t = max(segment.x, start);
  // `first`: the next step starts where the step grid restarts (the stretch's start, past a skipped
  // block, back after a stride): its length is jittered per pixel and frame, or a flat layer would
  // show rings where the steps reach its base at the same phase (equal distance from the camera).
  bool first = true;
  // An empty stride that lands in cloud is taken back: the march returns to its last empty sample
  // and steps up to where the stride landed (`refine_until`) in steps that do not stride.
  float stride_from = -1.0, refine_until = -1.0;
  float inverse_length = 1.0 / max(segment.y - segment.x, 1e-3);
  float phase_single = clouds_phase(mu, 1.0);
  // At least eight samples through each stretch: a layer crossed far away and steeply (seen from
  // orbit) would otherwise get one or two, and the jitter would decide whether the cloud is there.
  float longest_m = max(min(cl.max_step_m, (segment.y - segment.x) * 0.125), cl.min_step_m);
  while (t < segment.y && acc.steps < int(cl.max_steps) && acc.transmittance > 0.01) {
    // On to the next cloud sample. The empty samples are stepped over in a loop of their own: a
    // software rasteriser runs a loop's body for its whole group of pixels as long as any of them
    // needs it, so the light march below runs once per cloud sample of the group's pixels, not once
    // per step of its longest ray.
    float step_m = 0.0, density = 0.0;
    vec3 x = vec3(0.0);
    while (t < segment.y && acc.steps < int(cl.max_steps)) {
      // Steps grow with distance (a pixel's footprint grows with it), within [min, max].
      step_m = clamp(cl.min_step_m + t * cl.step_growth, cl.min_step_m, longest_m);
      float phase = first ? jitter : 1.0;  // an empty stride from here keeps the jitter too
      step_m *= phase, first = false;
      step_m = min(step_m, segment.y - t);
      x = dir * (t + 0.5 * step_m);
      ++acc.steps;
      clouds_footprint_m = (t + 0.5 * step_m) * cl.pixel_angle_rad;
      clouds_system_g =
          mix(e.system0, e.system1, clamp((t + 0.5 * step_m - segment.x) * inverse_length, 0.0, 1.0));
      // Whole blocks of empty weather are skipped without reading the noise.
      float skip = clouds_empty_skip(x, dir);
      if (skip > 0.0) {
        if (acc.depth_weight == 0.0) acc.clear_m = t + 0.5 * step_m;
        t += 0.5 * step_m + skip;  // from the sample to past the block's side
        first = true, stride_from = -1.0;
        continue;
      }
      bool empty;
      clouds_view_sample = true;
      density = clouds_density(layers, x, detail, false, empty);
      clouds_view_sample = false;
      if (density > 0.0 && stride_from >= 0.0) {
        // The stride's end lies at a phase of the stride's grid that is the same for every pixel at
        // this distance, and all that it passed counted as empty.
        refine_until = t + step_m, t = stride_from, stride_from = -1.0, first = true;
        continue;
      }
      if (density > 0.0) break;
      if (acc.depth_weight == 0.0) acc.clear_m = t + 0.5 * step_m;
      // Empty space: skip ahead by up to a quarter of the weather's texel (the weather cannot rise
      // from nothing to cloud much faster); where the noise eroded the cloud, the usual step.
      float stride =
          empty && t >= refine_until ? max(step_m, min(cl.max_step_m, cl.empty_step_m) * phase) : step_m;
      stride_from = stride > step_m ? t + 0.5 * step_m : -1.0;
      t += stride;
    }
    if (density <= 0.0) break;
    {
      // Before the light march evaluates other points.
      CloudsSampleGeometry geometry = clouds_sample_geometry();
      float sigma_t = density * extinction_per_density;
      float along = clamp((t - segment.x) * inverse_length, 0.0, 1.0);
      vec3 up = normalize(mix(e.up0, e.up1, along));
      vec3 e_light = mix(e.e_light0, e.e_light1, along), e_sky = mix(e.e_sky0, e.e_sky1, along);
      vec3 source = clouds_marched_source(layers, x, l, mu, phase_single, sigma_t, extinction_per_density,
                                          geometry, up, e_light, e_sky);
      // Energy-conserving step (Hillaire 2015): integrate the source over the step's own attenuation.
      float step_transmittance = exp(-sigma_t * step_m);
      vec3 step_light = source * (1.0 - step_transmittance);
      float opacity = acc.transmittance * (1.0 - step_transmittance);
#if CLOUDS_AP_MODE == 0
      vec3 ap_s = mix(e.ap_s0, e.ap_s1, along), ap_t = mix(e.ap_t0, e.ap_t1, along);
      acc.color += acc.transmittance * ap_t * step_light + ap_s * opacity;
#else
      acc.color += acc.transmittance * step_light;
#if CLOUDS_AP_MODE == 2
      if (!acc.ap_taken)
        acc.ap_inscattering = welkin_aerial_perspective(x, acc.ap_transmittance), acc.ap_taken = true;
#endif
#endif
      acc.weighted_depth += opacity * (t + 0.5 * step_m);
      acc.depth_weight += opacity;
      acc.transmittance *= step_transmittance;
      // Where the clouds become substantial (haze the camera flies through does not count).
      if (acc.transmittance < 0.9) acc.front = min(acc.front, t);
    }
    t += step_m;
  }
}

// The march through march pixel `pixel` (clouds_load() called first): colour and transmittance, and
// the clouds' opacity-weighted mean distance, where they turn opaque and up to where the ray met no
// cloud (m).
void clouds_march_pixel(ivec2 pixel, out vec4 color, out vec3 distances) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(cl.march_width, cl.march_height) * 2.0 - 1.0;
  vec3 dir = view_ray_direction(cl.inverse_view_projection, ndc);
  float t_max = scene_distance(ndc);
#if CLOUDS_CLUSTER_FRONT
  // The far clouds are drawn at a fraction of the march's resolution. The march stops at them where
  // the bilinear weights of their opaque texels around it reach one half (an edge that cuts across
  // their texels, not their squares' stair steps), at the farthest of those texels' fronts: behind a
  // cluster's edge the march goes on (what it adds there is seen through the edge).
  vec2 front_texel = (ndc * 0.5 + 0.5) * vec2(textureSize(u_cluster_front, 0)) - 0.5;
  vec2 f = front_texel - floor(front_texel);
  vec4 fronts = textureGather(u_cluster_front, ndc * 0.5 + 0.5, 0);  // (0, 1), (1, 1), (1, 0), (0, 0)
  vec4 weights = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
  vec4 opaque = vec4(lessThan(fronts, vec4(1e38)));
  vec4 finite = fronts * opaque;
  if (dot(weights, opaque) >= 0.5) t_max = min(t_max, max(max(finite.x, finite.y), max(finite.z, finite.w)));
#endif
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) t_max = min(t_max, ground.x);
  Accumulated acc =
      Accumulated(vec3(0.0), 1.0, 0.0, 0.0, cl.max_distance_m, false, vec3(0.0), vec3(1.0), 0, 0.0);
  float jitter = fract(texelFetch(u_blue_noise, pixel % 64, 0).r + cl.frame_index * 0.618034);
  jitter = 0.25 + 0.75 * jitter;  // the first step: never so short that it wastes a sample
  // The ray's stretches through each altitude band that holds layers (two per band at most: in
  // front of and behind the band's inner sphere), in order along the ray: the gaps between bands
  // (kilometres between a cumulus and a cirrus layer) are never stepped through.
  vec2 segments[2 * CLOUDS_MAX_BANDS];
  int segment_band[2 * CLOUDS_MAX_BANDS];
  int count = 0;
  float first = 3.4e38;
  // Indexed by a loop counter: copied out of the block first, so that a compiler that cannot keep a
  // dynamically indexed member in registers moves only these two vectors to memory, not the whole block.
  const vec4 band_low = cl.band_low, band_high = cl.band_high;
  for (int i = 0; i < CLOUDS_MAX_BANDS; ++i) {
    if (i >= int(cl.band_count)) break;
    vec2 outer = clouds_sphere(dir, band_high[i]), inner = clouds_sphere(dir, band_low[i]);
    if (outer.x > outer.y || outer.y <= 0.0) continue;
    vec2 a = vec2(max(outer.x, 0.0), outer.y), b = vec2(1.0, -1.0);
    if (inner.x <= inner.y && inner.y > 0.0) {
      b = vec2(max(inner.y, 0.0), outer.y);
      a.y = min(a.y, inner.x);
    }
    if (a.x < a.y) segment_band[count] = i, segments[count++] = a, first = min(first, a.x);
    if (b.x < b.y) segment_band[count] = i, segments[count++] = b, first = min(first, b.x);
  }
  // The march reaches max distance beyond where the ray first enters a band (from orbit, that is a
  // thousand kilometres away).
  t_max = min(t_max, first + cl.max_distance_m);
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && segments[j].x < segments[j - 1].x; --j) {
      vec2 swap = segments[j];
      segments[j] = segments[j - 1], segments[j - 1] = swap;
      int swap_band = segment_band[j];
      segment_band[j] = segment_band[j - 1], segment_band[j - 1] = swap_band;
    }
  float start = 0.0;
#if CLOUDS_SKIP
  start = clouds_skip_start(pixel, dir);
#endif
  // No cloud lies outside the bands, nor (last frame's rays tell) before the start.
  acc.clear_m = min(max(start, first), 1e9);
  for (int i = 0; i < count; ++i) {
    vec2 segment = vec2(segments[i].x, min(segments[i].y, t_max));
    if (segment.x < segment.y && start < segment.y) {
      // Each band with only the layers its samples and their light steps can reach (the others add
      // nothing there): a software rasteriser runs every compiled layer's code at every sample.
      SegmentEnds ends = segment_ends(dir, segment);
#if CLOUDS_BANDS > 0
      int band = segment_band[i];
      if (band == 0) march_segment(CLOUDS_BAND_LAYERS_0, dir, segment, ends, start, jitter, acc);
#if CLOUDS_BANDS > 1
      if (band == 1) march_segment(CLOUDS_BAND_LAYERS_1, dir, segment, ends, start, jitter, acc);
#endif
#if CLOUDS_BANDS > 2
      if (band == 2) march_segment(CLOUDS_BAND_LAYERS_2, dir, segment, ends, start, jitter, acc);
#endif
#if CLOUDS_BANDS > 3
      if (band == 3) march_segment(CLOUDS_BAND_LAYERS_3, dir, segment, ends, start, jitter, acc);
#endif
#else
      march_segment(CLOUDS_ALL_LAYERS, dir, segment, ends, start, jitter, acc);
#endif
    }
  }
#if CLOUDS_AP_MODE == 1
  if (acc.depth_weight > 0.0) {
    vec3 ap_t;
    vec3 ap_s = welkin_aerial_perspective(dir * (acc.weighted_depth / acc.depth_weight), ap_t);
    acc.color = acc.color * ap_t + ap_s * (1.0 - acc.transmittance);
  }
#elif CLOUDS_AP_MODE == 2
  acc.color = acc.color * acc.ap_transmittance + acc.ap_inscattering * (1.0 - acc.transmittance);
#endif
  color = vec4(max(acc.color, vec3(0.0)), acc.transmittance);
  float mean_m = acc.depth_weight > 0.0 ? acc.weighted_depth / acc.depth_weight : cl.max_distance_m;
  distances = vec3(mean_m, acc.front, acc.clear_m);
}
