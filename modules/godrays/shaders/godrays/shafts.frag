// The sunlight that shadowed air withholds along each view ray, at the shafts' resolution (rgb).
//   GODRAYS_METHOD 0 (marched): GODRAYS_STEPS jittered samples of the composed light environment's
//     visibility (every term that casts shadows), each step integrated against its own extinction,
//     S (1 - exp(-sigma_t dt)) / sigma_t, so thick air neither gains light nor divides by zero.
//   GODRAYS_METHOD 1 (screen space): the fraction of GODRAYS_SCREEN_SAMPLES depth taps toward the
//     sun's image that geometry covers, times the air's unshadowed sunlight along the ray.
#include "welkin/view.glsl"
// Many light samples per pixel: the light environment's terms may filter each less (one shadow tap).
#define WELKIN_VOLUME_SAMPLES 1
#include "welkin/lighting.glsl"

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

// Distance along the ray of the pixel at `texel` of the depth buffer to the geometry, or to the
// reach of the shafts where there is none nearer (reversed Z: 0 is nothing).
float ray_end_m(sampler2D depth_buffer, ivec2 texel, vec2 ndc) {
  float depth = texelFetch(depth_buffer, texel, 0).r;
  if (depth <= 0.0) return min(u_max_distance_m, ground_distance_m(view_ray_direction(u_inverse_view_projection, ndc)));
  vec4 p = u_inverse_view_projection * vec4(ndc, depth, 1.0);
  return min(length(p.xyz / p.w), u_max_distance_m);
}

in vec2 v_ndc;
layout(location = 0) out vec4 o_loss;
uniform vec2 u_sun_uv;  // the sun's image (screen space)
uniform float u_reach;  // fraction of the way to it the taps cover
uniform float u_jitter; // this frame's offset of the per-pixel noise
layout(binding = 0) uniform sampler2D u_depth;  // the frame's (reversed Z)

// Interleaved gradient noise (Jimenez 2014): a per-pixel offset in [0, 1) whose neighbours differ,
// so the samples' banding becomes fine noise that the upsampling and the eye average.
float pixel_noise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))) + u_jitter);
}

// Sunlight scattered toward the camera by the air on [0, end] of the ray, weighted by the shadow
// (1 - visibility) at each step (marched) or not at all (the screen-space estimate's air light).
vec3 air_light(vec3 dir, float end, int steps, float offset, bool shadowed) {
  vec3 light = vec3(0.0), transmittance = vec3(1.0);
  float dt = end / float(steps);
  for (int i = 0; i < steps; ++i) {
    vec3 p = dir * ((float(i) + offset) * dt);
    vec3 extinction;
    vec3 scattering = welkin_medium_scattering(p, dir, 0, extinction);
    float shadow = shadowed ? 1.0 - welkin_light_visibility(p, vec3(0.0), 0) : 1.0;
    vec3 step_t = exp(-extinction * dt);
    // (1 - e^{-x dt}) / x, with its limit dt where the air is empty.
    vec3 integral = mix(vec3(dt), (1.0 - step_t) / max(extinction, vec3(1e-30)), greaterThan(extinction * dt, vec3(1e-6)));
    light += transmittance * scattering * welkin_sun_irradiance(p) * (shadow * integral);
    transmittance *= step_t;
  }
  return light;
}

void main() {
  ivec2 size = textureSize(u_depth, 0);
  vec2 uv = v_ndc * 0.5 + 0.5;
  float end = ray_end_m(u_depth, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), v_ndc);
  vec3 dir = view_ray_direction(u_inverse_view_projection, v_ndc);
#if GODRAYS_JITTER
  float offset = pixel_noise(gl_FragCoord.xy);
#else
  float offset = 0.5;  // the reference: midpoints
#endif
#if GODRAYS_METHOD == 0
  vec3 loss = air_light(dir, end, GODRAYS_STEPS, offset, true);
#else
  float covered = 0.0;
  vec2 to_sun = (u_sun_uv - uv) * u_reach;
  for (int i = 0; i < GODRAYS_SCREEN_SAMPLES; ++i) {
    vec2 q = uv + to_sun * ((float(i) + offset) / float(GODRAYS_SCREEN_SAMPLES));
    float depth = texelFetch(u_depth, clamp(ivec2(q * vec2(size)), ivec2(0), size - 1), 0).r;
    covered += depth > 0.0 ? 1.0 : 0.0;
  }
  vec3 loss = (covered / float(GODRAYS_SCREEN_SAMPLES)) * air_light(dir, end, GODRAYS_AIR_STEPS, offset, false);
#endif
  o_loss = vec4(loss, 0.0);
}
