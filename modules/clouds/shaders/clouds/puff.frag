// One puff of the mesh clusters (a column of its cell through the layer, src/clusters.cpp), once per
// pixel its proxy covers. The view ray's chord through the box is clipped to the camera, the scene's
// depth, the planet and the clusters' stretch of the hand-over, and marched in PUFF_SAMPLES equal
// steps through the layer's own field (clouds/density.glsl, at the march's level of detail), each
// lit like a sample of the march (clouds/light_model.glsl). The optical depth toward the light comes
// from the clouds' shadow map at each sample (PUFF_SHADOW_MAP 1); else from the march's own light
// steps, found by the placement half way up and down the column and taken linear in height. Each
// sample fades as the complement of the march's hand-over, so the two paths' densities add up.
// PUFF_DETAIL 1: the detail noise erodes the samples, as in the march.
// PUFF_CANDIDATES > 1: each step reads the layer's weather alone (its envelope, before the noise) at
// that many points and takes its one sample of the field where the envelope is substantial nearest
// the camera, its optical depth scaled by the envelope's mean over the step against its value there.
// PUFF_LAYER: the clusters' layer (packed); only its field is marched (the march draws the others).
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/clusters.glsl"
#if PUFF_SHADOW_MAP
#include "welkin/lighting.glsl"
#endif
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(binding = 3) uniform sampler2D u_depth;  // the scene's (reversed Z; 0 = nothing)
uniform mat4 u_inverse_view_projection;         // camera-relative
uniform vec2 u_viewport;
uniform vec3 u_light_dir;
uniform vec3 u_range;  // near m, cross-fade m, far m (the march's hand-over)
in vec3 v_position;
flat in int v_puff;
flat in vec3 v_up;
flat in vec3 v_light, v_sky, v_ap_inscattering, v_ap_transmittance;
flat in float v_system_signal;
flat in vec4 v_light_gradient;  // w: the optical depth toward the light at the centre
layout(location = 0) out vec4 o_color;  // premultiplied: light reaching the camera, opacity
layout(location = 1) out float o_front;  // where the puff turns opaque (m; blended by minimum)

// Compiled in where the layers are (density.glsl), so that no other layer's weather or code runs.
#if CLOUDS_LAYERS > 0
#define PUFF_LAYERS (1 << PUFF_LAYER)
#define PUFF_LAYER_BLOCK cl_local_layers[PUFF_LAYER]
#define PUFF_FOLLOWS_MAP CLOUDS_HAS(CLOUDS_MAP_MASK, PUFF_LAYER)
#else
#define PUFF_LAYERS CLOUDS_ALL_LAYERS
#define PUFF_LAYER_BLOCK cl_layers[PUFF_LAYER]
#define PUFF_FOLLOWS_MAP (cl_layers[PUFF_LAYER].follows_map > 0.5)
#endif

// What the layer's weather allows at x before the noise erodes it (one read of the weather).
float puff_envelope(vec3 x) {
  clouds_footprint_m = length(x) * cl.pixel_angle_rad;
  clouds_painted_sample = 2.0;
#if CLOUDS_LAYERS > 0 && CLOUDS_ANVILS
  clouds_layer_anvil = CLOUDS_HAS(CLOUDS_ANVIL_MASK, PUFF_LAYER) ? 1 : 0;
#endif
  float t, d0;
  return clouds_layer_envelope(PUFF_LAYER_BLOCK, clouds_weather_fetch(PUFF_LAYER_BLOCK, x), PUFF_FOLLOWS_MAP,
                               x, clouds_altitude(x), t, d0);
}

// Where along the step [t_from, t_from + step_m] of the ray `dir` its one sample of the field is read,
// and by how much its optical depth is scaled (`scale`); < 0: the weather allows no cloud in the step.
// One sample at the step's middle reads clear air where the step's other parts hold cloud, and cloud
// where they hold none: the columns covered the band a fifth less than the march, in patches. The
// envelope (one weather read a point, no noise) finds the step's cloud: the sample is taken at the
// nearest point whose envelope reaches half the step's largest (where the march's opacity would
// build up: the visible front, not an eroded fringe), and the step's optical depth is what the
// sample's extinction gives where the envelope is its mean over the step (the noise's erosion
// taken as the sample's along the step). The scale lies within [0, 2].
float puff_step_sample(vec3 dir, float t_from, float step_m, out float scale) {
  scale = 1.0;
#if PUFF_CANDIDATES > 1
  float e[PUFF_CANDIDATES], e_sum = 0.0, e_max = 0.0;
  for (int j = 0; j < PUFF_CANDIDATES; ++j) {
    e[j] = puff_envelope(dir * (t_from + (float(j) + 0.5) / float(PUFF_CANDIDATES) * step_m));
    e_sum += e[j], e_max = max(e_max, e[j]);
  }
  if (e_max <= 0.0) return -1.0;
  int pick = 0;
  for (int j = PUFF_CANDIDATES - 1; j >= 0; --j)
    if (e[j] >= 0.5 * e_max) pick = j;
  scale = e_sum / (float(PUFF_CANDIDATES) * e[pick]);
  return t_from + (float(pick) + 0.5) / float(PUFF_CANDIDATES) * step_m;
#else
  return t_from + 0.5 * step_m;
#endif
}

void main() {
  clouds_load();
  vec3 centre = cp_puffs[v_puff].centre, radii = cp_puffs[v_puff].radii;
  vec3 dir = normalize(v_position);
  // The ray in the box's normalised frame (the box becomes [-1, 1]^3; t stays in metres).
  vec3 o = puff_local(vec3(0.0), centre, radii), d = puff_direction(dir, radii);
  vec3 inverse_d = 1.0 / max(abs(d), vec3(1e-12)) * sign(d + vec3(1e-30));
  vec3 ta = (-1.0 - o) * inverse_d, tb = (1.0 - o) * inverse_d;
  vec3 t_in = min(ta, tb), t_out = max(ta, tb);
  float t0 = max(max(t_in.x, t_in.y), max(t_in.z, 0.0)), t1 = min(min(t_out.x, t_out.y), t_out.z);
  vec2 uv = gl_FragCoord.xy / u_viewport;  // the puffs may be drawn at a fraction of the frame's size
  float depth = textureLod(u_depth, uv, 0.0).r;
  if (depth > 0.0) {
    vec4 q = u_inverse_view_projection * vec4(uv * 2.0 - 1.0, depth, 1.0);
    t1 = min(t1, length(q.xyz / q.w));
  }
  // The planet hides what lies beyond its surface (a cluster past the horizon).
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) t1 = min(t1, ground.x);
  // Only where the clusters draw the layer (their fade, below, is zero nearer than the hand-over's
  // start and beyond far): the steps sample that stretch alone, and the front (where the march
  // stops) is never nearer than it. Columns of cells that straddle the hand-over reach nearer; with
  // their whole chord in one step, the front could lie at the box's near face, inside the march's
  // own stretch.
  t0 = max(t0, u_range.x - 0.5 * u_range.y), t1 = min(t1, u_range.z);
  if (t1 <= t0) discard;
  float mu = dot(dir, u_light_dir);
  float phase_single = clouds_phase(mu, 1.0);
  clouds_system_g = v_system_signal;
  float extinction_per_density = cp_puffs[v_puff].extinction_per_density;
  const int n = PUFF_SAMPLES;
  float step_m = (t1 - t0) / float(n);
  vec3 color = vec3(0.0);
  float transmittance = 1.0, front = 3.4e38;
  for (int k = 0; k < n; ++k) {
    float scale;
    float t = puff_step_sample(dir, t0 + float(k) * step_m, step_m, scale);
    if (t < 0.0) continue;
    vec3 x = dir * t;
    clouds_footprint_m = t * cl.pixel_angle_rad;
    float density = clouds_density(PUFF_LAYERS, x, PUFF_DETAIL != 0, false);
    if (density <= 0.0) continue;
    float r = length(x);
    float fade = smoothstep(u_range.x - 0.5 * u_range.y, u_range.x + 0.5 * u_range.y + 1e-3, r) *
                 (1.0 - smoothstep(u_range.z - u_range.y - 1e-3, u_range.z, r));
    float sigma = density * extinction_per_density * fade;
#if PUFF_SHADOW_MAP
    // The clouds' shadow map at the sample: the whole way toward the sun, the layer's own cloud included.
    float tau = clouds_shadow_optical_depth(x);
#else
    float tau = max(v_light_gradient.w + v_light_gradient.z * (o.z + d.z * t), 0.0);
#endif
    CloudsLightInputs s = clouds_light_inputs(tau, sigma, clouds_depth_below_m, clouds_depth_above_m);
    s.column_below = clouds_column_below, s.column_above = clouds_column_above, s.fill = clouds_fill;
    vec3 source = clouds_diffusion_model
                      ? clouds_light_source(mu, phase_single, s, u_light_dir, v_up, v_light, v_sky)
                      : clouds_sample_source(mu, phase_single, tau, sigma, clouds_depth_below_m,
                                             clouds_depth_above_m, u_light_dir, v_up, v_light, v_sky);
    // Energy-conserving step (Hillaire 2015), as the march's.
    float step_transmittance = exp(-sigma * scale * step_m);
    color += transmittance * source * (1.0 - step_transmittance);
    float before = transmittance;
    transmittance *= step_transmittance;
    // Opaque beyond one half (the march stops there).
    if (before >= 0.5 && transmittance < 0.5)
      front = t - 0.5 * step_m +
              step_m * clamp(log(before / 0.5) / max(sigma * scale * step_m, 1e-12), 0.0, 1.0);
  }
  float opacity = 1.0 - transmittance;
  if (opacity < 1e-5) discard;
  o_color = vec4(v_ap_transmittance * color + v_ap_inscattering * opacity, opacity);
  o_front = front;
}
