#pragma once
// The sunlight that shadowed air withholds along each view ray, at the shafts' resolution (rgb), and
// the distance the ray was followed (a).
//   GODRAYS_METHOD 0 (marched): GODRAYS_SEGMENTS x GODRAYS_SUBSTEPS jittered samples of the composed
//     light environment's visibility (every term that casts shadows), weighting the air's light.
//   GODRAYS_METHOD 1 (screen space): the fraction of GODRAYS_SCREEN_SAMPLES depth taps toward the
//     sun's image that geometry covers, times the air's unshadowed sunlight along the ray.
#include "godrays/view_ray.glsl"
// Many light samples per pixel: the light environment's terms may filter each less (one shadow tap).
#define WELKIN_VOLUME_SAMPLES 1
#include "welkin/lighting.glsl"

#include "godrays/haze.glsl"

layout(binding = 0) uniform sampler2D u_depth;  // the frame's (reversed Z)

// Interleaved gradient noise (Jimenez 2014): a per-pixel offset in [0, 1) whose neighbours differ,
// so the samples' banding becomes fine noise that the upsampling and the eye average.
float pixel_noise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))) + gr.jitter);
}

// Sunlight the air (and the haze) at p scatters toward the camera per metre, and their extinction.
vec3 medium_source(vec3 p, vec3 dir, out vec3 extinction) {
  vec3 scattering = welkin_medium_scattering(p, dir, 0, extinction);
#if GODRAYS_HAZE
  float density = haze_density(p);
  extinction += density * haze_extinction_per_density();
  scattering += density * gr.haze_scattering * haze_phase(dot(dir, welkin_sun_direction()));
#endif
  return scattering * welkin_sun_irradiance(p);
}

// Integral over one step of length dt of e^{k t} (per channel), with its limit dt (1 + k dt / 2) where
// k dt is too small for the difference of exponentials.
vec3 step_integral(vec3 k, float dt) {
  vec3 x = k * dt;
  return mix(dt * (1.0 + 0.5 * x), (exp(x) - 1.0) / k, greaterThan(abs(x), vec3(1e-4)));
}

// Sunlight scattered toward the camera by the air on [0, end] of the ray, weighted by the shadow
// (1 - visibility) of each of `substeps` jittered samples in each of `segments` equal segments
// (marched), or unweighted (the screen-space estimate's air light). The air is looked up at the ends of
// the segments only: within one, the light a metre of ray sends to the camera, g = T s E, is taken as
// exponential in distance (exact for one exponential layer and constant extinction), so each sample's
// share of it is the last one's times e^{k dt}. Extinction is integrated over each segment as a
// trapezoid; the sum of the shares is the segment's whole integral, so fully lit air takes nothing.
vec3 air_light(vec3 dir, float end, int segments, int substeps, float offset, bool shadowed) {
  float length_m = end / float(segments), dt = length_m / float(substeps);
  vec3 extinction0, transmittance = vec3(1.0);
  vec3 source0 = medium_source(vec3(0.0), dir, extinction0);
  vec3 light = vec3(0.0);
  for (int j = 0; j < segments; ++j) {
    vec3 p1 = dir * (float(j + 1) * length_m), extinction1;
    vec3 source1 = medium_source(p1, dir, extinction1);
    vec3 transmittance1 = transmittance * exp(-0.5 * (extinction0 + extinction1) * length_m);
    vec3 g0 = max(transmittance * source0, vec3(1e-30)), g1 = max(transmittance1 * source1, vec3(1e-30));
    vec3 k = log(g1 / g0) / length_m;
    vec3 share = g0 * step_integral(k, dt), ratio = exp(k * dt);
    for (int m = 0; m < substeps; ++m) {
      float shadow = shadowed
                         ? 1.0 - welkin_light_visibility(
                                     dir * (float(j) * length_m + (float(m) + offset) * dt), vec3(0.0), 0)
                         : 1.0;
      light += shadow * share;
      share *= ratio;
    }
    transmittance = transmittance1, source0 = source1, extinction0 = extinction1;
  }
  return light;
}

// The loss of the shafts' texel whose centre is at v_ndc (normalised device coordinates) and `centre`
// (texels).
vec4 shafts_texel(vec2 v_ndc, vec2 centre) {
  ivec2 size = textureSize(u_depth, 0);
  vec2 uv = v_ndc * 0.5 + 0.5;
  float end = min(scene_distance_m(u_depth, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), v_ndc),
                  gr.max_distance_m);
  vec3 dir = view_ray_direction(gr.inverse_view_projection, v_ndc);
#if GODRAYS_JITTER
  float offset = pixel_noise(centre);
#else
  float offset = 0.5;  // the reference: midpoints
#endif
#if GODRAYS_METHOD == 0
  vec3 loss = air_light(dir, end, GODRAYS_SEGMENTS, GODRAYS_SUBSTEPS, offset, true);
#else
  float covered = 0.0;
  vec2 to_sun = (vec2(gr.sun_u, gr.sun_v) - uv) * gr.reach;
  for (int i = 0; i < GODRAYS_SCREEN_SAMPLES; ++i) {
    vec2 q = uv + to_sun * ((float(i) + offset) / float(GODRAYS_SCREEN_SAMPLES));
    float depth = texelFetch(u_depth, clamp(ivec2(q * vec2(size)), ivec2(0), size - 1), 0).r;
    covered += depth > 0.0 ? 1.0 : 0.0;
  }
  vec3 loss =
      (covered / float(GODRAYS_SCREEN_SAMPLES)) * air_light(dir, end, GODRAYS_AIR_STEPS, 1, offset, false);
#endif
  return vec4(loss, end);  // a: where the ray ends, for the filter's edges
}
