#pragma once
// The cloud density field, shared by the march, the light march and the shadow map (and mirrored in
// C++ by validation/cloud_field.cpp for the CPU reference). Points are camera-relative metres; lengths in
// the planet-centred frame come from the camera's radius so that float precision does not depend on
// the planet's size (altitude h = h_camera + (r^2 - r_camera^2) / (r + r_camera)).

// The frame block and a layer, declared once for GLSL and C++ (src/frame_block.h).
#include "clouds/blocks.glsl.h"
// Per frame (src/frame_block.cpp fills it, std140).
layout(std140, binding = 0) uniform CloudsFrame { CloudsFrameGpu clb; };
// The block in a private variable, loaded once per invocation (clouds_load): software rasterisers
// reload uniform and storage blocks at every use inside a loop.
CloudsFrameGpu cl;
const int CLOUDS_MAX_BANDS = 4;

// The layers (src/frame_block.cpp packs them, std430).
layout(std430, binding = 0) readonly buffer CloudLayers { CloudLayerGpu cl_layers[]; };
// Up to four layers are copied into private variables too; more are read from the buffer.
const int CLOUDS_LOCAL_LAYERS = 4;
CloudLayerGpu cl_local_layers[CLOUDS_LOCAL_LAYERS];
int cl_layer_count = 0;

// Call first in every shader that uses the field.
void clouds_load() {
  cl = clb;
  cl_layer_count = int(cl.layer_count);
  for (int i = 0; i < CLOUDS_LOCAL_LAYERS; ++i)
    if (i < cl_layer_count) cl_local_layers[i] = cl_layers[i];
}


layout(binding = 0) uniform sampler3D cl_shape_noise;     // r shape; gba the curl field as 0.5 + 0.5 c
layout(binding = 1) uniform sampler3D cl_detail_noise;
layout(binding = 2) uniform sampler3D cl_weather_noise;
layout(binding = 5) uniform sampler3D cl_weather_maximum;  // 16^3 blocks a level: the largest signal in each
layout(binding = 6) uniform sampler2D cl_coverage_map;     // painted coverage (128: none), north row first
layout(binding = 7) uniform sampler3D cl_weather_systems;  // the weather systems' signal (uniform on [0, 1])

// The width a sample stands for (a pixel's footprint at its distance): the noise is read at the
// mip level whose texels match it, so distant clouds average instead of aliasing. Set by the caller.
float clouds_footprint_m = 0.0;
float clouds_lod(float texel_m) { return log2(max(clouds_footprint_m / texel_m, 1.0)); }

float clouds_altitude(vec3 x) {
  float r_c = cl.camera_radius_m;
  float d = 2.0 * r_c * dot(cl.up, x) + dot(x, x);  // r^2 - r_camera^2
  float r = sqrt(max(r_c * r_c + d, 0.0));
  return cl.camera_altitude_m + d / max(r + r_c, 1.0);
}

// What a layer's weather and vertical envelope allow at x, before the noise erodes it (also the
// coarse occupancy that lets the march skip empty space without fetching the shape noise).
// One sample's noise, read once and shared by the layers: the shape and detail noise are the same for
// every layer, and layers of one genus read the weather at the same place (in other channels).
// Reset by clouds_density for each new point.
vec4 clouds_shape_sample = vec4(-1.0);  // x < 0: not read yet
float clouds_detail_sample = -1.0;
// The displacement (m) the detail sample was read with: a layer whose base turbulence differs at this
// point reads it again.
#ifndef CLOUDS_TURBULENCE
#define CLOUDS_TURBULENCE 0
#endif
float clouds_detail_displacement = 0.0;
// The cloud below the last point clouds_density evaluated: its layers' depth under the point (m),
// weighted by their density there (the light reflected up from it).
float clouds_depth_below_m = 0.0;
// And its depth over the point, up to the top of its column as the weather shapes it (m).
float clouds_depth_above_m = 0.0;
// The optical depths of the column under and over the point at the density the weather gives it
// before the noise erodes it (the cloud's body, where the point itself may be a thin wisp).
float clouds_column_below = 0.0, clouds_column_above = 0.0;
// How much of the un-eroded envelope the noise left at the point (1: solid; small: between billows,
// where light diffused in the cloud leaks out through the gaps): the layers' eroded extinction over
// their envelope's, both summed over the layers.
float clouds_fill = 1.0, clouds_envelope_sigma = 0.0;
float clouds_painted_sample = 2.0;  // > 1: not read yet at this point
// CLOUDS_HANDOVER: some layer is handed over to the mesh clusters beyond a distance; the march sets
// this while it samples what the camera sees (not toward the light).
#ifndef CLOUDS_HANDOVER
#define CLOUDS_HANDOVER 0
#endif
bool clouds_view_sample = false;

// The weather systems' signal where the caller marches: it changes over hundreds of kilometres, so
// the caller looks it up at the ends of each stretch it marches and interpolates (like the light),
// instead of reading it at every sample. Neutral until set.
float clouds_system_g = 0.5;
float clouds_weather_system_at(vec3 x) {
  return textureLod(cl_weather_systems, cl.system_origin + x * cl.system_per_m, 0.0).r;
}
// A layer's coverage c where the weather systems' signal is g (frame_block.cpp's
// system_coverage): raised where g > 0.5, lowered where g < 0.5, by up to the amount times 4 c (1 - c),
// so that 0 and 1 stay clear and overcast.
float clouds_system_coverage(float c, float g) {
  return clamp(c + cl.system_amount * (2.0 * g - 1.0) * 4.0 * c * (1.0 - c), 0.0, 1.0);
}

// The coverage the painted map adds at x: the point is projected along the planet's radius onto the
// map's tangent plane (a column of air reads one texel at every altitude); 0 off the map.
float clouds_painted_coverage(vec3 x) {
  if (clouds_painted_sample <= 1.5) return clouds_painted_sample;
  vec3 q = cl.map_origin + vec3(dot(x, cl.map_east), dot(x, cl.map_north), dot(x, cl.map_up));
  clouds_painted_sample = 0.0;
  if (q.z <= 0.0) return 0.0;
  vec2 uv = vec2(q.x, -q.y) * (cl.map_scale / q.z) + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 0.0;
  clouds_painted_sample = (textureLod(cl_coverage_map, uv, 0.0).r * 255.0 - 128.0) / 127.0;
  return clouds_painted_sample;
}

#include "clouds/genus_shapes.glsl"

// The weather sample a layer reads at x (its three genus channels and the base's variation): a
// streaked genus's weather is stretched along its wind too (bands of fibres).
vec4 clouds_weather_fetch(CloudLayerGpu L, vec3 x) {
  return textureLod(cl_weather_noise, L.weather_origin + clouds_stretched(L, x) * L.weather_per_m,
                    clouds_lod(1.0 / (L.weather_per_m * 64.0)));
}

// Scales what the weather allows (the billboards' bake windows the field around each cloud it bakes).
float clouds_weather_scale = 1.0;

// The top of a layer's column (a fraction of its thickness) where the weather's strength over the
// coverage threshold is a (0 at the threshold, 1 at the strongest weather): domes rise fast from
// their edge and round over, and since the strength does not saturate inside a cloud neither do they
// (no plateaus, no outlines traced by the weather's texels); sheets fill the layer.
float clouds_layer_top(CloudLayerGpu L, float a) {
  return mix(1.0, max(1.0 - (1.0 - a) * (1.0 - a), 0.1), L.dome);
}
// Where the envelope clouds_layer_envelope last evaluated has fallen half way (a fraction of the
// layer's thickness): the top of its column, as the light sees it.
float clouds_envelope_top = 1.0;
// How much of that envelope is the anvil's (0: none; genera.h): the noise erodes it less.
float clouds_anvil_weight = 0.0;

// The flat-based domes or sheets of a layer, where its weather signal w is d0 over the threshold lo
// (rising over the filter's width) at height t in the layer.
float clouds_dome_envelope(CloudLayerGpu L, float w, float lo, float d0, float t) {
  if (d0 <= 0.0) return 0.0;
  float top = clouds_layer_top(L, clamp((w - lo) / max(1.0 - lo, L.filter_width), 0.0, 1.0));
  float u = t / top;
  if (u >= 1.0) return 0.0;
  // Flat bases; over the column the density falls as 1 - u^k toward the top: rounded domes (k 2),
  // sheets even to near their top (k 6). The noise then carves the billows out of the rounded part.
  float k = mix(6.0, 2.0, L.dome);
  clouds_envelope_top = top * exp2(-1.0 / k);
  return d0 * smoothstep(0.0, 0.06, t) * (1.0 - pow(u, k));
}

// `w4`: the layer's weather sample at x; `follows_map`: the painted map adds to its coverage.
float clouds_layer_envelope(CloudLayerGpu L, vec4 w4, bool follows_map, vec3 x, float h, out float t,
                            out float d0) {
  t = 0.0, d0 = 0.0, clouds_anvil_weight = 0.0;
  if (h < L.base_m - L.base_variation_m || h > L.base_m + L.thickness_m + L.base_variation_m) return 0.0;
  float c = clouds_system_coverage(L.coverage, clouds_system_g);
  if (follows_map) c = clamp(c + clouds_painted_coverage(x), 0.0, 1.0);
  if (c <= 0.0) return 0.0;
  int channel = int(L.weather_channel);
  float w = channel == 0 ? w4.r : channel == 1 ? w4.g : w4.b;
  float base = L.base_m + L.base_variation_m * (w4.a - 0.5) * 2.0;
  t = (h - base) / max(L.thickness_m, 1e-3);
  if (t <= 0.0 || t >= 1.0) return 0.0;
  // Coverage c covers a fraction c of the sky (the weather channels are equalised to uniform).
  float fw = L.filter_width;
  float lo = (1.0 - c) * (1.0 + fw) - fw;
  d0 = clamp((w - lo) / fw, 0.0, 1.0) * clouds_weather_scale;
  float e = clouds_dome_envelope(L, w, lo, d0, t);
#if CLOUDS_ANVILS
  if (clouds_layer_anvil > 0 || (clouds_layer_anvil < 0 && L.anvil_start > 0.0)) {
    float a0, a = clouds_anvil(L, w, lo, t, a0);
    a0 *= clouds_weather_scale, a *= clouds_weather_scale;
    if (a > e) clouds_envelope_top = 0.97, d0 = max(d0, a0);
    e = max(e, a);
    clouds_anvil_weight = e > 0.0 ? a / e : 0.0;
  }
#endif
  return e;
}

// The detail noise at xd (what the layers erode with).
float clouds_detail_fetch(vec3 xd) {
  return textureLod(cl_detail_noise, cl.detail_origin + xd * cl.detail_per_m,
                    clouds_lod(1.0 / (cl.detail_per_m * 32.0)))
      .r;
}

// Extinction (1/m) of one layer at x, from the shape sample already read (clouds_shape_sample);
// `detail` adds the detail noise's erosion. `envelope` is what the weather allowed before any noise
// (0: empty space the march may skip).
float clouds_layer_density(CloudLayerGpu L, vec4 w4, bool follows_map, bool detail, vec3 x, float h,
                           out float envelope) {
  float t, d0;
  envelope = clouds_layer_envelope(L, w4, follows_map, x, h, t, d0);
  if (envelope <= 0.0) return 0.0;
  vec4 s4 = clouds_shape_sample;
#if CLOUDS_STREAKS
  // A streaked layer reads the shape and detail noise in its own frame.
  bool streaked =
      clouds_layer_streaks > 0 || (clouds_layer_streaks < 0 && (L.streak > 1.0 || L.hook_m != 0.0));
  vec3 xs = vec3(0.0);
  if (streaked) {
    xs = clouds_streaked(L, x, t);
    s4 = textureLod(cl_shape_noise, L.streak_shape_origin + xs * cl.shape_per_m,
                    clouds_lod(1.0 / (cl.shape_per_m * 128.0)));
  }
#endif
  float s = s4.x;
  // The shape noise is equalised (noise_volumes.cpp): shape_amount 1 erodes up to 60% of the density,
  // enough for heaps with gaps and lobes, not so much that they fall apart into shreds.
  float erosion = (1.0 - s) * L.shape_amount * 0.6;
#if CLOUDS_ANVILS
  // The anvil's cloud has spread out smooth and flat: the noise hardly carves it.
  erosion *= 1.0 - 0.8 * clouds_anvil_weight;
#endif
  float d = clamp((envelope - erosion) / max(1.0 - erosion, 1e-3), 0.0, 1.0);
  if (detail && d > 0.0 && L.detail_amount > 0.0) {
    float n;
#if CLOUDS_STREAKS
    if (streaked) {
#if CLOUDS_TURBULENCE
      // The curl field moves the point as for any layer (below), in the streaked frame.
      float k = cl.turbulence_m * d0 * clamp(1.0 - t / 0.3, 0.0, 1.0);
      n = clouds_streaked_detail_fetch(L, clouds_streaked(L, x + (s4.yzw * 2.0 - 1.0) * k, t));
#else
      n = clouds_streaked_detail_fetch(L, xs);
#endif
    } else {
#endif
#if CLOUDS_TURBULENCE
    // Curl turbulence (Schneider 2015): the detail noise is read where the curl field, fetched with
    // the shape, moves the point; in the lowest 30% of the layer, as far as the weather there holds
    // cloud (takram's weighting). A compile-time switch: a software rasteriser pays for the
    // arithmetic of a branch even where no pixel takes it.
    float k = cl.turbulence_m * d0 * clamp(1.0 - t / 0.3, 0.0, 1.0);
    if (k != clouds_detail_displacement || clouds_detail_sample < 0.0) {
      clouds_detail_displacement = k;
      clouds_detail_sample = clouds_detail_fetch(x + (s4.yzw * 2.0 - 1.0) * k);
    }
#else
    // Read once per point for every layer (clouds_density), before the layers.
    if (clouds_detail_sample < 0.0) clouds_detail_sample = clouds_detail_fetch(x);
#endif
    n = clouds_detail_sample;
#if CLOUDS_STREAKS
    }
#endif
    // Wisps at the base, billows above (Schneider 2015's height blend): the inverted Worley noise
    // erodes between its cells' centres and leaves rounded lobes, the Worley noise erodes at the
    // centres and leaves the cells' thin walls; each as deep as the genus erodes (genera.h).
    float e = mix(L.wisp * n, L.billow * (1.0 - n), smoothstep(0.05, 0.35, t)) * L.detail_amount;
#if CLOUDS_ANVILS
    e *= 1.0 - 0.6 * clouds_anvil_weight;
#endif
    d = clamp((d - e) / max(1.0 - e, 1e-3), 0.0, 1.0);
  }
  // The density rises over the first 1 / edge of the eroded field inside its edge (crisp heaps, soft
  // veils), and follows the layer's vertical profile.
  float profile = clamp(
      L.profile_exp_term * exp(L.profile_exponent * t) + L.profile_linear_term * t + L.profile_constant_term,
      0.0, 1.0);
  d = min(d * L.edge, 1.0) * profile;
  clouds_envelope_sigma += min(envelope * L.edge, 1.0) * profile * L.density_per_m;
  clouds_fill += d * L.density_per_m;
#if CLOUDS_HANDOVER
  // Seen from the camera, a layer the mesh clusters take over fades out across the hand-over; its
  // light and shadow samples keep the whole layer (the clusters' clouds still shade what is near).
  if (clouds_view_sample && L.handover_near_m > 0.0) {
    // The complement of the puffs' fade (clusters_place.comp): in across [near - w/2, near + w/2],
    // out across [far - w, far]; the two paths' densities add up to the field's.
    float r = length(x);
    d *= 1.0 - smoothstep(L.handover_near_m - 0.5 * L.handover_crossfade_m,
                          L.handover_near_m + 0.5 * L.handover_crossfade_m + 1e-3, r) *
                   (1.0 - smoothstep(L.handover_far_m - L.handover_crossfade_m - 1e-3, L.handover_far_m, r));
  }
#endif
  clouds_depth_below_m += d * L.density_per_m * t * L.thickness_m;
  float above_m = max(clouds_envelope_top - t, 0.0) * L.thickness_m;
  clouds_depth_above_m += d * L.density_per_m * above_m;
  // The column's body: the weather's density before the noise erodes it, risen as the edge makes it.
  float body = min(d0 * L.edge, 1.0) * L.density_per_m;
  clouds_column_below += d * L.density_per_m * (body * t * L.thickness_m);
  clouds_column_above += d * L.density_per_m * (body * above_m);
  return d * L.density_per_m;
}

// The field's layers are compiled in (CLOUDS_LAYERS of them, at most CLOUDS_LOCAL_LAYERS), each with
// what it needs and nothing else, so that a software rasteriser (which runs both sides of every
// branch for its whole group of pixels) does not pay for what no layer uses. Bit i of a mask is
// layer i's (density_field.cpp's field_defines writes them):
//   CLOUDS_DETAIL_MASK  the detail noise erodes it;  CLOUDS_MAP_MASK  it follows the painted map;
//   CLOUDS_SHADOW_MASK  it casts shadows;  CLOUDS_STREAK_MASK  it streaks;  CLOUDS_ANVIL_MASK  it has
//   an anvil;  CLOUDS_WEATHER_SOURCE_i  the layer (<= i) whose weather sample it shares (the same place
//   and period, other channels).
// CLOUDS_LAYERS 0: any number of layers, read from the buffer with run-time checks.
#ifndef CLOUDS_LAYERS
#define CLOUDS_LAYERS 0
#endif
#ifndef CLOUDS_DETAIL_MASK
#define CLOUDS_DETAIL_MASK 15
#define CLOUDS_MAP_MASK 15
#define CLOUDS_SHADOW_MASK 15
#define CLOUDS_WEATHER_SOURCE_1 1
#define CLOUDS_WEATHER_SOURCE_2 2
#define CLOUDS_WEATHER_SOURCE_3 3
#endif
#ifndef CLOUDS_STREAK_MASK
#define CLOUDS_STREAK_MASK 15
#endif
#ifndef CLOUDS_ANVIL_MASK
#define CLOUDS_ANVIL_MASK 15
#endif
#define CLOUDS_HAS(mask, i) ((((mask) >> (i)) & 1) != 0)
#define CLOUDS_ALL_LAYERS 15

// Layer i's value of `fn` at x into arr[i], or layer s's already there when the two read the same
// weather (s < i); the condition is a compile-time constant, so the unneeded side is not compiled.
#define CLOUDS_SHARED(arr, fn, i, s) \
  arr[i] = (s) == (i) ? fn(cl_local_layers[i], x) : arr[(s) == (i) ? 0 : (s)];
#define CLOUDS_FOR_COMPILED_LAYERS(arr, fn)                          \
  arr[0] = fn(cl_local_layers[0], x);                                \
  if (CLOUDS_LAYERS > 1) { CLOUDS_SHARED(arr, fn, 1, CLOUDS_WEATHER_SOURCE_1) } \
  if (CLOUDS_LAYERS > 2) { CLOUDS_SHARED(arr, fn, 2, CLOUDS_WEATHER_SOURCE_2) } \
  if (CLOUDS_LAYERS > 3) { CLOUDS_SHARED(arr, fn, 3, CLOUDS_WEATHER_SOURCE_3) }

// The same for the compiled layers in `layers` (bit i: layer i; a compile-time constant where the
// caller passes one, as the march does per altitude band): a weather sample that none of them reads
// is not fetched, and the others' code is not compiled in.
#define CLOUDS_SOURCE_OF(i)          \
  ((i) == 0   ? 0                    \
   : (i) == 1 ? CLOUDS_WEATHER_SOURCE_1 \
   : (i) == 2 ? CLOUDS_WEATHER_SOURCE_2 \
              : CLOUDS_WEATHER_SOURCE_3)
#define CLOUDS_READS_WEATHER(j, s) (CLOUDS_HAS(layers, j) && CLOUDS_SOURCE_OF(j) == (s))
#define CLOUDS_READS(s)                                      \
  (CLOUDS_READS_WEATHER(0, s) || CLOUDS_READS_WEATHER(1, s) || \
   CLOUDS_READS_WEATHER(2, s) || CLOUDS_READS_WEATHER(3, s))
#define CLOUDS_MASKED_SHARED(arr, fn, i)                                         \
  arr[i] = CLOUDS_SOURCE_OF(i) != (i) ? arr[CLOUDS_SOURCE_OF(i) == (i) ? 0 : CLOUDS_SOURCE_OF(i)] \
           : CLOUDS_READS(i)          ? fn(cl_local_layers[i], x)                                  \
                                      : vec4(0.0);
#define CLOUDS_FOR_MASKED_LAYERS(arr, fn)                       \
  CLOUDS_MASKED_SHARED(arr, fn, 0)                              \
  if (CLOUDS_LAYERS > 1) { CLOUDS_MASKED_SHARED(arr, fn, 1) }   \
  if (CLOUDS_LAYERS > 2) { CLOUDS_MASKED_SHARED(arr, fn, 2) }   \
  if (CLOUDS_LAYERS > 3) { CLOUDS_MASKED_SHARED(arr, fn, 3) }

#define CLOUDS_ADD_LAYER(i)                                                                           \
  if (CLOUDS_HAS(layers, i) && (!shadow_only || CLOUDS_HAS(CLOUDS_SHADOW_MASK, i))) {                 \
    clouds_layer_streaks = CLOUDS_HAS(CLOUDS_STREAK_MASK, i) ? 1 : 0;                                 \
    clouds_layer_anvil = CLOUDS_HAS(CLOUDS_ANVIL_MASK, i) ? 1 : 0;                                    \
    sum += clouds_layer_density(cl_local_layers[i], w[i], CLOUDS_HAS(CLOUDS_MAP_MASK, i),             \
                                detail && CLOUDS_HAS(CLOUDS_DETAIL_MASK, i), x, h, envelope);         \
    clouds_layer_streaks = -1, clouds_layer_anvil = -1;                                               \
    empty = empty && envelope <= 0.0;                                                                 \
  }

// Total extinction of the layers at x (shadow_only: only layers that cast shadows; `layers`: only those
// of them, as above); `empty` when no layer's weather allows cloud there. `detail`: the detail noise
// erodes the layers that use it.
float clouds_density(int layers, vec3 x, bool detail, bool shadow_only, out bool empty) {
  empty = true;
  clouds_detail_sample = -1.0, clouds_painted_sample = 2.0;
  clouds_detail_displacement = 0.0;
  clouds_depth_below_m = 0.0, clouds_depth_above_m = 0.0;
  clouds_column_below = 0.0, clouds_column_above = 0.0;
  clouds_fill = 0.0, clouds_envelope_sigma = 0.0;
  float h = clouds_altitude(x);
  if (h < cl.lowest_m || h > cl.highest_m) return 0.0;
  // The shape noise is the same for every layer that does not streak (those read their own): read once.
#if CLOUDS_LAYERS > 0
  const bool shared_shape = (((1 << CLOUDS_LAYERS) - 1) & ~CLOUDS_STREAK_MASK & layers) != 0;
#else
  const bool shared_shape = true;
#endif
  if (shared_shape)
    clouds_shape_sample = textureLod(cl_shape_noise, cl.shape_origin + x * cl.shape_per_m,
                                     clouds_lod(1.0 / (cl.shape_per_m * 128.0)));
  float sum = 0.0, envelope;
#if CLOUDS_LAYERS > 0
#if !CLOUDS_TURBULENCE
  if (detail && (CLOUDS_DETAIL_MASK & ~CLOUDS_STREAK_MASK & layers) != 0)
    clouds_detail_sample = clouds_detail_fetch(x);
#endif
  vec4 w[CLOUDS_LOCAL_LAYERS];
  CLOUDS_FOR_MASKED_LAYERS(w, clouds_weather_fetch)
  CLOUDS_ADD_LAYER(0)
  if (CLOUDS_LAYERS > 1) { CLOUDS_ADD_LAYER(1) }
  if (CLOUDS_LAYERS > 2) { CLOUDS_ADD_LAYER(2) }
  if (CLOUDS_LAYERS > 3) { CLOUDS_ADD_LAYER(3) }
#else
  detail = detail && cl.shape_detail > 0.5;
  vec4 weather_at = vec4(-1.0), w4 = vec4(0.0);
  for (int i = 0; i < cl_layer_count; ++i) {
    CloudLayerGpu L = cl_layers[i];
    if (shadow_only && L.casts_shadow < 0.5) continue;
    vec4 weather = vec4(L.weather_origin, L.weather_per_m);
    if (weather != weather_at) weather_at = weather, w4 = clouds_weather_fetch(L, x);
    sum += clouds_layer_density(L, w4, L.follows_map > 0.5, detail, x, h, envelope);
    empty = empty && envelope <= 0.0;
  }
#endif
  clouds_depth_below_m /= max(sum, 1e-12);
  clouds_depth_above_m /= max(sum, 1e-12);
  clouds_column_below /= max(sum, 1e-12), clouds_column_above /= max(sum, 1e-12);
  clouds_fill = clouds_envelope_sigma > 0.0 ? min(clouds_fill / clouds_envelope_sigma, 1.0) : 1.0;
  return sum;
}
float clouds_density(vec3 x, bool detail, bool shadow_only, out bool empty) {
  return clouds_density(CLOUDS_ALL_LAYERS, x, detail, shadow_only, empty);
}
float clouds_density(int layers, vec3 x, bool detail, bool shadow_only) {
  bool empty;
  return clouds_density(layers, x, detail, shadow_only, empty);
}
float clouds_density(vec3 x, bool detail, bool shadow_only) {
  bool empty;
  return clouds_density(CLOUDS_ALL_LAYERS, x, detail, shadow_only, empty);
}

// The occupancy of a layer's weather around x: the largest signal in the 16^3 block x lies in, over
// the weather's levels that a fetch in the block may read (each level is equalised, and a coarser
// texel may exceed every finer one: weather_levels.h). A skip goes at most the largest block further
// along the view ray, where a pixel's footprint has grown by its angle times that; the weather's
// trilinear read there blends the levels either side of log2(footprint / texel): up to its ceiling (a
// 64th over for a GL's fixed-point level of detail).
const int CLOUDS_WEATHER_LEVELS = 7;  // weather_levels.h: kWeatherLevels
vec4 clouds_weather_block(CloudLayerGpu L, vec3 x) {
  vec3 cells = fract(L.weather_origin + clouds_stretched(L, x) * L.weather_per_m) * 16.0;
  float texels = (clouds_footprint_m + cl.largest_block_m * cl.pixel_angle_rad) * L.weather_per_m * 64.0;
  int level = clamp(int(ceil(log2(max(texels, 1e-6)) + 1.0 / 64.0)), 0, CLOUDS_WEATHER_LEVELS - 1);
  ivec3 block = clamp(ivec3(cells), ivec3(0), ivec3(15));
  return texelFetch(cl_weather_maximum, block + ivec3(0, 0, 16 * level), 0);
}

// How far the march may go from x along dir without passing any cloud: to the far side of the
// occupancy block x lies in, when no layer within reach (altitudes widened by the largest block) can
// hold cloud anywhere in its block. 0 when one might. `m`: the layer's block maximum.
float clouds_skip_layer(CloudLayerGpu L, vec4 m, vec3 x, vec3 dir, float h, float skip) {
  float reach = 1.8 * cl.largest_block_m;
  if (h < L.base_m - L.base_variation_m - reach || h > L.base_m + L.thickness_m + L.base_variation_m + reach)
    return skip;
  int channel = int(L.weather_channel);
  float w = channel == 0 ? m.r : channel == 1 ? m.g : m.b;
  // The weather systems may raise the coverage anywhere in the block by what their signal changes
  // over the block, and by what interpolating it along the stretch may miss (0.03: a stretch of
  // 200 km across their finest features); a layer that follows the painted map may be as covered as
  // the map's largest texel makes it.
  float block_m = 1.0 / (16.0 * L.weather_per_m);
  float g = min(clouds_system_g + cl.system_slope_per_m * 1.8 * block_m + 0.03, 1.0);
  float fw = L.filter_width,
        c = min(clouds_system_coverage(L.coverage, g) + L.follows_map * max(cl.map_raise, 0.0), 1.0);
  float lo = (1.0 - c) * (1.0 + fw) - fw;
  if (w > lo - clouds_anvil_reach(L, lo)) return 0.0;  // an anvil may reach past the layer's threshold
  // Metres to the block's far side along dir (cells per metre: 16 x the layer's 1 / period).
  vec3 f = fract(fract(L.weather_origin + clouds_stretched(L, x) * L.weather_per_m) * 16.0);
  vec3 rate = abs(clouds_stretched(L, dir)) * (16.0 * L.weather_per_m) + 1e-12;
  vec3 to_side = mix(f, 1.0 - f, step(0.0, dir)) / rate;
  return min(skip, min(to_side.x, min(to_side.y, to_side.z)) + 1.0);
}

float clouds_empty_skip(vec3 x, vec3 dir) {
  float h = clouds_altitude(x), skip = cl.largest_block_m;
#if CLOUDS_LAYERS > 0
  // Layers that share a weather sample share its block too.
  vec4 m[CLOUDS_LOCAL_LAYERS];
  CLOUDS_FOR_COMPILED_LAYERS(m, clouds_weather_block)
  skip = clouds_skip_layer(cl_local_layers[0], m[0], x, dir, h, skip);
  if (CLOUDS_LAYERS > 1) skip = clouds_skip_layer(cl_local_layers[1], m[1], x, dir, h, skip);
  if (CLOUDS_LAYERS > 2) skip = clouds_skip_layer(cl_local_layers[2], m[2], x, dir, h, skip);
  if (CLOUDS_LAYERS > 3) skip = clouds_skip_layer(cl_local_layers[3], m[3], x, dir, h, skip);
#else
  for (int i = 0; i < cl_layer_count && skip > 0.0; ++i) {
    CloudLayerGpu L = cl_layers[i];
    skip = clouds_skip_layer(L, clouds_weather_block(L, x), x, dir, h, skip);
  }
#endif
  return skip;
}

// Distances along a ray from a camera-relative origin to the sphere at `altitude` above the
// planet's surface: (near, far), or near > far when missed. Differences of squares are formed first
// (R^2 - r_c^2 = (R - r_c)(R + r_c)) so that precision does not depend on the planet's size.
vec2 clouds_sphere_from(vec3 origin, vec3 dir, float altitude) {
  float R = cl.planet_radius_m + altitude;
  float r_c = cl.camera_radius_m;
  float b = r_c * dot(cl.up, dir) + dot(origin, dir);
  float c =
      (altitude - cl.camera_altitude_m) * (R + r_c) - (2.0 * r_c * dot(cl.up, origin) + dot(origin, origin));
  float disc = b * b + c;
  if (disc < 0.0) return vec2(1.0, -1.0);
  float s = sqrt(disc);
  return vec2(-b - s, -b + s);
}
vec2 clouds_sphere(vec3 dir, float altitude) { return clouds_sphere_from(vec3(0.0), dir, altitude); }
