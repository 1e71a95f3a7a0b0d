// One puff of the mesh clusters, once per pixel its proxy covers (the mesh from its far side, so a
// camera inside it still sees it). The view ray's chord through the ellipsoid is clipped to the
// camera, the scene's depth and the planet (soft where it meets terrain, exact where the camera
// enters) and cut flat at the cluster's base; its transmittance has a closed form. Its light is
// taken at samples stratified by opacity (each stands for an equal share of what the puff hides),
// each lit like a sample of the march (clouds/light_model.glsl) with the optical depth toward the
// light through the puff itself and through the cluster's other puffs (found at its centre and
// across it, interpolated). PUFF_SAMPLES: the light's samples per pixel.
#include "clouds/density.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/clusters.glsl"
layout(std430, binding = 1) readonly buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
layout(binding = 3) uniform sampler2D u_depth;  // the scene's (reversed Z; 0 = nothing)
uniform mat4 u_inverse_view_projection;         // camera-relative
uniform vec2 u_viewport;
uniform vec3 u_light_dir;
in vec3 v_position;
flat in int v_puff;
flat in vec4 v_base_plane;  // up at the puff; w: the camera's height above the cluster's base (m)
flat in vec3 v_light, v_sky, v_ap_inscattering, v_ap_transmittance;
flat in float v_height_m;         // the puff's centre above the cluster's base
flat in vec4 v_light_gradient;  // w: the depth toward the light at the centre
layout(location = 0) out vec4 o_color;  // premultiplied: light reaching the camera, opacity
layout(location = 1) out float o_front;  // where the puff turns opaque (m; blended by minimum)

void main() {
  // What the light model reads of the block.
  cl = clb;
  // The puff's fields are loaded as they are needed: most of a quad's pixels stop at the chord.
  vec3 centre = cp_puffs[v_puff].centre, radii = cp_puffs[v_puff].radii;
  vec3 dir = normalize(v_position);
  vec3 camera_local = puff_local(vec3(0.0), centre, radii), dir_local = puff_direction(dir, radii);
  vec4 chord = puff_chord_local(camera_local, dir_local);
  if (chord.w <= 0.0) discard;
  // Cut at the cluster's base (a plane across the local vertical): flat bases, as the field's.
  float t0 = 0.0, t1 = 3.4e38;
  float rate = dot(dir, v_base_plane.xyz), above = v_base_plane.w;  // height above the base: rate t + above
  if (abs(rate) > 1e-6) {
    float t_base = -above / rate;
    if (rate > 0.0) t0 = max(t0, t_base);
    else t1 = min(t1, t_base);
  } else if (above < 0.0) {
    discard;
  }
  if (chord.x + chord.w <= t0 || chord.x - chord.w >= t1) discard;
  vec2 uv = gl_FragCoord.xy / u_viewport;  // the puffs may be drawn at a fraction of the frame's size
  float depth = textureLod(u_depth, uv, 0.0).r;
  if (depth > 0.0) {
    vec4 q = u_inverse_view_projection * vec4(uv * 2.0 - 1.0, depth, 1.0);
    t1 = min(t1, length(q.xyz / q.w));
  }
  // The planet hides what lies beyond its surface (a cluster past the horizon).
  vec2 ground = clouds_sphere(dir, 0.0);
  if (ground.x <= ground.y && ground.x > 0.0) t1 = min(t1, ground.x);
  float s0 = clamp(t0 - chord.x, -chord.w, chord.w), s1 = clamp(t1 - chord.x, -chord.w, chord.w);
  if (s1 <= s0) discard;
  float sigma = cp_puffs[v_puff].extinction_per_m;
  float depth_total = sigma * (puff_depth_at(chord, s1) - puff_depth_at(chord, s0));
  float opacity = 1.0 - exp(-depth_total);
  if (opacity < 1e-5) discard;
  vec3 up = v_base_plane.xyz;
  float mu = dot(dir, u_light_dir);
  float phase_single = clouds_phase(mu, 1.0);
  // Toward the light, in the puff's normalised frame (the same for every sample).
  vec3 light_local = puff_direction(u_light_dir, radii);
  float light_a = max(dot(light_local, light_local), 1e-30);
  vec3 source = vec3(0.0);
  const int n = PUFF_SAMPLES;
  for (int k = 0; k < n; ++k) {
    // The sample that hides the k-th equal share of the puff's opacity.
    float share = (float(k) + 0.5) / float(n) * opacity;
    float s = puff_invert_depth(chord, s0, s1, -log(1.0 - share) / sigma);
    vec3 local = camera_local + dir_local * (chord.x + s);
    float q = chord.z + chord.y * s * s;  // squared normalised radius there
    // Through the puff to the light: from the sample (t = 0) to where the light's ray leaves it.
    float t_mid = -dot(local, light_local) / light_a;
    vec3 closest = local + light_local * t_mid;
    vec4 toward_light = vec4(t_mid, light_a, dot(closest, closest), 0.0);
    toward_light.w = toward_light.z < 1.0 ? sqrt((1.0 - toward_light.z) / light_a) : -1.0;
    // And through the cluster's other puffs: linear across this one, never below zero.
    float tau = sigma * puff_optical_depth(toward_light, 0.0, 3.4e38) +
                max(v_light_gradient.w + dot(v_light_gradient.xyz, local), 0.0);
    // The cloud under the sample, from the cluster's base (the march's depth in its layer).
    float depth_below_m = max(v_height_m + local.z * radii.z, 0.0);
    // And over it, to the puff's top (the cluster's other puffs are not above it).
    float depth_above_m = max(sqrt(max(1.0 - dot(local.xy, local.xy), 0.0)) - local.z, 0.0) * radii.z;
    source += clouds_sample_source(mu, phase_single, tau, sigma * max(1.0 - q, 0.0), depth_below_m,
                                   depth_above_m, u_light_dir, up, v_light, v_sky);
  }
  vec3 light = source * (opacity / float(n));
  o_color = vec4(v_ap_transmittance * light + v_ap_inscattering * opacity, opacity);
  // Opaque beyond one half: where the depth reaches ln 2 (else nowhere).
  o_front = depth_total > 0.6931472 ? chord.x + puff_invert_depth(chord, s0, s1, 0.6931472 / sigma) : 3.4e38;
}
