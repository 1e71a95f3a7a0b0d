// One billboard, once per pixel its quad covers. BILLBOARDS_RENDER_VOLUME 0: the impostor: each of
// the three views around the viewing direction is read where the pixel's ray meets its plane (through
// the box's centre, across the view), blended by weight and opacity, and lit once at the point that
// hides half of the opacity, with the optical depth toward the light recovered from the texel's
// harmonics. 1: the reference: the pixel's ray marched through the archetype's volume, each sample
// lit through a march toward the light. Both light like the march (clouds/light_model.glsl), and
// both are clipped by the scene's depth and the planet.
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/billboards.glsl"
#if BILLBOARDS_SHADOW_MAP
#include "welkin/lighting.glsl"
#endif
layout(binding = 3) uniform sampler2D u_depth;  // the scene's (reversed Z; 0 = nothing)
#if !BILLBOARDS_RENDER_VOLUME
layout(binding = 4) uniform sampler2DArray u_atlas_texture;  // 2 layers per view and archetype
layout(binding = 8) uniform sampler2DArray u_fill_atlas;     // 1 layer per view and archetype: the fill
#endif
uniform mat4 u_inverse_view_projection;  // camera-relative
uniform vec2 u_viewport;
uniform vec3 u_light_dir;
in vec3 v_position;
flat in vec3 v_wind, v_across, v_up;
flat in vec4 v_plane[3], v_axis_a[3], v_axis_b[3];
flat in vec3 v_layers, v_weights;
flat in int v_billboard;
flat in float v_scale;
layout(std430, binding = 1) readonly buffer Billboards { Billboard bb_billboards[]; };
layout(location = 0) out vec4 o_color;  // premultiplied: light reaching the camera, opacity
layout(location = 1) out float o_front;  // where the billboard turns opaque (m; blended by minimum)

vec3 to_local(vec3 v) { return vec3(dot(v, v_wind), dot(v, v_across), dot(v, v_up)); }

// Where the scene's depth or the planet's surface ends the ray (m).
float ray_end(vec3 dir) {
  float t_end = 3.4e38;
  vec2 uv_screen = gl_FragCoord.xy / u_viewport;
  float depth = textureLod(u_depth, uv_screen, 0.0).r;
  if (depth > 0.0) {
    vec4 q = u_inverse_view_projection * vec4(uv_screen * 2.0 - 1.0, depth, 1.0);
    t_end = length(q.xyz / q.w);
  }
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) t_end = min(t_end, ground.x);
  return t_end;
}

// The optical depth toward the light at x (camera-relative) of a billboard's sample whose own
// archetype's cloud gives `own`. The archetype is a cloud alone: the neighbours that shade it in the
// field are missing (at a sun 25 degrees up the billboards were 28% brighter than the march), and the
// field's own depth at x (the clouds' shadow map) is that of a cloud that is not the archetype: alone,
// it made them 17% darker there and 11% brighter at noon. The two are averaged (docs/clouds-far.md,
// "The billboards' light from the shadow map"). Beyond the map (its largest cascade, which reads no
// depth outside: clouds/light_term.glsl) the archetype's alone, faded in over its outer 5%.
float billboard_light_depth(float own, vec3 x) {
#if BILLBOARDS_SHADOW_MAP
  int k = max(cs.cascade_count - 1, 0);
  vec3 q = x - cs.cascades[k].origin;
  vec2 c = vec2(0.5 + dot(q, cs.cascades[k].axis_u), 0.5 + dot(q, cs.cascades[k].axis_v));
  float inside = clamp(min(min(c.x, 1.0 - c.x), min(c.y, 1.0 - c.y)) / 0.05, 0.0, 1.0);
  return mix(own, 0.5 * (own + clouds_shadow_optical_depth(x)), inside);
#else
  return own;
#endif
}

void main() {
  vec3 dir = normalize(v_position);
  float scale = v_scale;
  vec3 light;
  float opacity, front = 3.4e38;
  cl = clb;
  vec3 l_local = to_local(u_light_dir);
  float mu = dot(dir, u_light_dir);
#if BILLBOARDS_RENDER_VOLUME
  // The reference: 64 steps through the box, each lit through 24 steps toward the light.
  float phase_single = clouds_phase(mu, 1.0);
  float t_end = ray_end(dir);
  Billboard b = bb_billboards[v_billboard];
  int archetype = int(b.archetype);
  vec3 o = to_local(-b.centre), d = to_local(dir);
  vec2 span = billboard_box_span(o, d);
  span.x = max(span.x, 0.0), span.y = min(span.y, t_end);
  if (span.y <= span.x) discard;
  float dt = (span.y - span.x) / 64.0, transmittance = 1.0;
  light = vec3(0.0);
  for (int s = 0; s < 64; ++s) {
    float t = span.x + (float(s) + 0.5) * dt;
    vec3 p = o + d * t;
    vec2 sigma_fill = billboard_extinction_fill(p, archetype);
    float sigma = sigma_fill.x * scale;
    if (sigma <= 0.0) continue;
    float tau = billboard_light_depth(billboard_march_depth(p, l_local, archetype, 24) * scale, dir * t);
    float step_opacity = 1.0 - exp(-sigma * dt);
    float below_m = max(p.z + u_volume.y, 0.0), above_m = max(u_box.y - p.z, 0.0);
    CloudsLightInputs inputs = clouds_light_inputs(tau, sigma, below_m, above_m);
    inputs.fill = sigma_fill.y;
    light += transmittance * step_opacity *
             (clouds_diffusion_model
                  ? clouds_light_source(mu, phase_single, inputs, u_light_dir, v_up, b.light, b.sky)
                  : clouds_sample_source(mu, phase_single, tau, sigma, below_m, above_m, u_light_dir, v_up,
                                         b.light, b.sky));
    if (transmittance > 0.5 && transmittance * (1.0 - step_opacity) <= 0.5) front = t;
    transmittance *= 1.0 - step_opacity;
  }
  opacity = 1.0 - transmittance;
#else
  // Each view where the ray meets its plane: opacity first, the rest only where there is cloud.
  opacity = 0.0;
  vec3 uvw[3];
  vec4 a[3];
  float t_plane[3], view_opacity[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = vec4(0.0), view_opacity[i] = 0.0;
    float along = dot(dir, v_plane[i].xyz);
    if (v_weights[i] <= 0.0 || abs(along) < 1e-6) continue;
    t_plane[i] = v_plane[i].w / along;
    vec2 uv = t_plane[i] * vec2(dot(dir, v_axis_a[i].xyz), dot(dir, v_axis_b[i].xyz)) +
              vec2(v_axis_a[i].w, v_axis_b[i].w);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
    uvw[i] = vec3(uv, v_layers[i]);
    a[i] = textureLod(u_atlas_texture, uvw[i], 0.0);
    view_opacity[i] = 1.0 - exp(-a[i].x * scale);
    opacity += v_weights[i] * view_opacity[i];
  }
  if (opacity < 1e-5) discard;
  float weight = 0.0, t_half = 0.0, height = 0.0, sigma = 0.0, fill = 0.0;
  vec4 sh_diffuse = vec4(0.0);
  for (int i = 0; i < 3; ++i) {
    float w = v_weights[i] * view_opacity[i];
    if (w <= 0.0) continue;
    weight += w;
    t_half += w * (t_plane[i] + a[i].y * u_box.z);
    height += w * a[i].z;
    sigma += w * a[i].w;
    sh_diffuse += w * textureLod(u_atlas_texture, uvw[i] + vec3(0.0, 0.0, 1.0), 0.0);
    fill += w * textureLod(u_fill_atlas, vec3(uvw[i].xy, floor(0.5 * uvw[i].z)), 0.0).r;
  }
  t_half /= weight, height /= weight, sigma /= weight, sh_diffuse /= weight, fill /= weight;
  // Soft where the scene or the planet comes within the cloud's half height of its middle.
  opacity *= clamp((ray_end(dir) - t_half) / u_box.y + 0.5, 0.0, 1.0);
  // The averaged diffuse transmittance toward the light, and the optical depth it stands for (the
  // direct beam's own average, kept in a third layer, measured no better: 10.0% against 10.1%).
  float tau = scale * (1.0 / billboard_transmittance(sh_diffuse, l_local, 0.02) - 1.0) / 0.15;
  tau = billboard_light_depth(tau, dir * t_half);
  float phase_single = clouds_phase(mu, 1.0);
  Billboard b = bb_billboards[v_billboard];
  float above_m = max(u_volume.y + u_box.y - height, 0.0);  // to the box's top
  CloudsLightInputs inputs = clouds_light_inputs(tau, sigma * scale, max(height, 0.0), above_m);
  inputs.fill = fill;
  vec3 source = clouds_diffusion_model
      ? clouds_light_source(mu, phase_single, inputs, u_light_dir, v_up, b.light, b.sky)
      : clouds_sample_source(mu, phase_single, tau, sigma * scale, max(height, 0.0), above_m,
                             u_light_dir, v_up, b.light, b.sky);
  light = opacity * source;
  if (opacity > 0.5) front = t_half;
#endif
  if (opacity < 1e-5) discard;
  o_color = vec4(b.ap_transmittance * light + b.ap_inscattering * opacity, opacity);
  o_front = front;
}
