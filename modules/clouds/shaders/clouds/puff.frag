// One puff of the mesh clusters, drawn from its far side (so a camera inside it still sees it): the
// view ray's chord through the ellipsoid, clipped to the camera and the scene's depth (soft where it
// meets terrain, exact where the camera enters) and cut flat at the cluster's base, its transmittance in closed form, and its light at
// samples stratified by opacity (each stands for an equal share of what the puff hides), lit like a
// sample of the march (clouds/light_model.glsl) with the optical depth toward the light through the
// puff itself and through the cluster's other puffs (found at its centre and across it, interpolated).
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/clusters.glsl"
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(binding = 3) uniform sampler2D u_depth;  // the scene's (reversed Z; 0 = nothing)
uniform mat4 u_inverse_view_projection;         // camera-relative
uniform vec2 u_viewport;
uniform vec3 u_light_dir;
uniform int u_samples;
uniform float u_layer_base_m;  // the light reflected up from the cloud below is the march's: from the layer's base
in vec3 v_position;
flat in int v_puff;
layout(location = 0) out vec4 o_color;  // premultiplied: light reaching the camera, opacity
layout(location = 1) out float o_front;  // where the puff turns opaque (m; blended by minimum)

void main() {
  // What the light model reads of the block.
  cl_phase = clb_phase, cl_medium = clb_medium, cl_light = clb_light, cl_light_model = clb_light_model;
  cl_planet = clb_planet, cl_up = clb_up;
  ClusterPuff p = cp_puffs[v_puff];
  vec3 dir = normalize(v_position);
  vec4 chord = puff_chord(vec3(0.0), dir, p.centre.xyz, p.radii.xyz);
  float depth = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
  float scene = 3.4e38;
  if (depth > 0.0) {
    vec4 q = u_inverse_view_projection * vec4(gl_FragCoord.xy / u_viewport * 2.0 - 1.0, depth, 1.0);
    scene = length(q.xyz / q.w);
  }
  // The planet hides what lies beyond its surface (a cluster past the horizon).
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) scene = min(scene, ground.x);
  float t0 = 0.0, t1 = scene;
  // Cut at the cluster's base (a plane across the local vertical): flat bases, as the field's.
  vec3 up = normalize(cl_up.xyz * cl_planet.z + p.centre.xyz);
  float rate = dot(dir, up), above = p.sky.w - dot(p.centre.xyz, up);  // height above the base: rate t + above
  if (abs(rate) > 1e-6) {
    float t_base = -above / rate;
    if (rate > 0.0) t0 = max(t0, t_base);
    else t1 = min(t1, t_base);
  } else if (above < 0.0) {
    discard;
  }
  float s0 = clamp(t0 - chord.x, -chord.w, chord.w), s1 = clamp(t1 - chord.x, -chord.w, chord.w);
  if (chord.w <= 0.0 || s1 <= s0) discard;
  float sigma = p.centre.w;
  float depth_total = sigma * (puff_depth_at(chord, s1) - puff_depth_at(chord, s0));
  float opacity = 1.0 - exp(-depth_total);
  if (opacity < 1e-5) discard;
  float mu = dot(dir, u_light_dir);
  float phase_single = clouds_phase(mu, 1.0);
  vec3 source = vec3(0.0);
  int n = u_samples;
  for (int k = 0; k < n; ++k) {
    // The sample that hides the k-th equal share of the puff's opacity.
    float share = (float(k) + 0.5) / float(n) * opacity;
    float s = puff_invert_depth(chord, s0, s1, -log(1.0 - share) / sigma);
    vec3 x = dir * (chord.x + s);
    float q = chord.z + chord.y * s * s;  // squared normalised radius at x
    vec4 toward_light = puff_chord(x, u_light_dir, p.centre.xyz, p.radii.xyz);
    // Through the cluster's other puffs: linear across this one, never below zero.
    vec3 local = vec3(dot(x - p.centre.xyz, u_axis_wind), dot(x - p.centre.xyz, u_axis_across), dot(x - p.centre.xyz, u_axis_up)) / p.radii.xyz;
    float tau = sigma * puff_optical_depth(toward_light, 0.0, 3.4e38) + max(p.radii.w + dot(p.light_gradient.xyz, local), 0.0);
    float depth_below_m = max(clouds_altitude(x) - u_layer_base_m, 0.0);
    source += clouds_sample_source(mu, phase_single, tau, sigma * max(1.0 - q, 0.0), depth_below_m, u_light_dir, up,
                                   p.light.rgb, p.sky.rgb);
  }
  vec3 light = source * (opacity / float(n));
  o_color = vec4(p.ap_transmittance.rgb * light + p.ap_inscattering.rgb * opacity, opacity);
  // Opaque beyond one half: where the depth reaches ln 2 (else nowhere).
  o_front = depth_total > 0.6931472 ? chord.x + puff_invert_depth(chord, s0, s1, 0.6931472 / sigma) : 3.4e38;
}
