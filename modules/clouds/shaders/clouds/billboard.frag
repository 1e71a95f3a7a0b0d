// One billboard, once per pixel its quad covers. BILLBOARDS_RENDER_VOLUME 0: the impostor: each of
// the four views around the viewing direction is read where the pixel's ray meets its plane (through
// the box's centre, across the view), blended by weight and opacity, and lit once at the point that
// hides half of the opacity, with the optical depth toward the light recovered from the texel's
// harmonics. 1: the reference: the pixel's ray marched through the archetype's volume, each sample
// lit through a march toward the light. Both light like the march (clouds/light_model.glsl), and
// both are clipped by the scene's depth and the planet.
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/billboards.glsl"
layout(std430, binding = 1) readonly buffer Billboards { Billboard bb_billboards[]; };
layout(binding = 3) uniform sampler2D u_depth;  // the scene's (reversed Z; 0 = nothing)
#if !BILLBOARDS_RENDER_VOLUME
layout(binding = 4) uniform sampler3D u_atlas_texture;  // 2 layers per view and archetype
#endif
uniform mat4 u_inverse_view_projection;  // camera-relative
uniform vec2 u_viewport;
uniform vec3 u_light_dir;
in vec3 v_position;
flat in int v_billboard;
flat in vec3 v_wind, v_across, v_up;
flat in ivec4 v_views;
flat in vec4 v_weights;
layout(location = 0) out vec4 o_color;  // premultiplied: light reaching the camera, opacity
layout(location = 1) out float o_front;  // where the billboard turns opaque (m; blended by minimum)

vec3 to_local(vec3 v) { return vec3(dot(v, v_wind), dot(v, v_across), dot(v, v_up)); }
vec3 to_world(vec3 v) { return v.x * v_wind + v.y * v_across + v.z * v_up; }

void main() {
  cl_phase = clb_phase, cl_medium = clb_medium, cl_light = clb_light, cl_light_model = clb_light_model;
  cl_planet = clb_planet, cl_up = clb_up;
  Billboard b = bb_billboards[v_billboard];
  vec3 dir = normalize(v_position), c = b.centre.xyz;
  float scale = b.centre.w;
  int archetype = int(b.sky.w);
  // What hides the billboard: the scene's depth and the planet's surface.
  float t_end = 3.4e38;
  vec2 uv_screen = gl_FragCoord.xy / u_viewport;
  float depth = textureLod(u_depth, uv_screen, 0.0).r;
  if (depth > 0.0) {
    vec4 q = u_inverse_view_projection * vec4(uv_screen * 2.0 - 1.0, depth, 1.0);
    t_end = length(q.xyz / q.w);
  }
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) t_end = min(t_end, ground.x);
  vec3 l_local = to_local(u_light_dir);
  float mu = dot(dir, u_light_dir);
  float phase_single = clouds_phase(mu, 1.0);
  vec3 light;
  float opacity, front = 3.4e38;
#if BILLBOARDS_RENDER_VOLUME
  // The reference: 64 steps through the box, each lit through 24 steps toward the light.
  vec3 o = to_local(-c), d = to_local(dir);
  vec2 span = billboard_box_span(o, d);
  span.x = max(span.x, 0.0), span.y = min(span.y, t_end);
  if (span.y <= span.x) discard;
  float dt = (span.y - span.x) / 64.0, transmittance = 1.0;
  light = vec3(0.0);
  for (int s = 0; s < 64; ++s) {
    float t = span.x + (float(s) + 0.5) * dt;
    vec3 p = o + d * t;
    float sigma = billboard_extinction(p, archetype) * scale;
    if (sigma <= 0.0) continue;
    float tau = billboard_march_depth(p, l_local, archetype, 24) * scale;
    float step_opacity = 1.0 - exp(-sigma * dt);
    light += transmittance * step_opacity *
             clouds_sample_source(mu, phase_single, tau, sigma, max(p.z + u_volume.y, 0.0), u_light_dir, v_up, b.light.rgb, b.sky.rgb);
    if (transmittance > 0.5 && transmittance * (1.0 - step_opacity) <= 0.5) front = t;
    transmittance *= 1.0 - step_opacity;
  }
  opacity = 1.0 - transmittance;
#else
  opacity = 0.0;
  float weight = 0.0, t_half = 0.0, height = 0.0, sigma = 0.0;
  vec4 sh = vec4(0.0);
  float layers = float(2 * u_atlas.z * u_atlas.x * u_atlas.y);
  for (int i = 0; i < 4; ++i) {
    if (v_weights[i] <= 0.0) continue;
    int v = v_views[i];
    vec3 d = billboard_view_direction(v / u_atlas.x, v % u_atlas.x), right, up;
    billboard_view_axes(d, right, up);
    vec3 n = to_world(d);
    float along = dot(dir, n);
    if (abs(along) < 1e-6) continue;
    float t = dot(c, n) / along;  // where the ray meets the view's plane
    vec3 hit = dir * t - c;
    vec2 uv = vec2(dot(hit, to_world(right)), dot(hit, to_world(up))) / u_box.z * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
    float layer = float(2 * (archetype * u_atlas.x * u_atlas.y + v));
    vec4 a = textureLod(u_atlas_texture, vec3(uv, (layer + 0.5) / layers), 0.0);
    float view_opacity = 1.0 - exp(-a.x * scale);
    float w = v_weights[i] * view_opacity;
    opacity += v_weights[i] * view_opacity;
    weight += w;
    t_half += w * (t + a.y * u_box.z);
    height += w * a.z;
    sigma += w * a.w;
    sh += w * textureLod(u_atlas_texture, vec3(uv, (layer + 1.5) / layers), 0.0);
  }
  if (weight <= 1e-6) discard;
  t_half /= weight, height /= weight, sigma /= weight, sh /= weight;
  // Soft where the scene or the planet comes within the cloud's half height of its middle.
  opacity *= clamp((t_end - t_half) / u_box.y + 0.5, 0.0, 1.0);
  float tau = billboard_light_depth(sh, l_local) * scale;
  light = opacity * clouds_sample_source(mu, phase_single, tau, sigma * scale, max(height, 0.0), u_light_dir, v_up, b.light.rgb, b.sky.rgb);
  if (opacity > 0.5) front = t_half;
#endif
  if (opacity < 1e-5) discard;
  o_color = vec4(b.ap_transmittance.rgb * light + b.ap_inscattering.rgb * opacity, opacity);
  o_front = front;
}
