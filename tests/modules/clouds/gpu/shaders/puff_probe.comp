// Evaluates the puffs' closed forms (clouds/clusters.glsl) for the CPU's rays: the optical depth of
// a stretch of each ray through its puff, and where the depth from the stretch's start reaches a target.
#include "clouds/clusters.glsl"
layout(local_size_x = 64) in;
struct ProbeRay {
  vec4 origin;  // w: t0
  vec4 dir;     // w: t1
  vec4 centre;  // w: target depth (unit extinction)
  vec4 radii;
};
layout(std430, binding = 0) readonly buffer Rays { ProbeRay rays[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };  // depth, t at the target, half length, t_mid
uniform int u_count;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  ProbeRay r = rays[i];
  vec4 chord = puff_chord(r.origin.xyz, r.dir.xyz, r.centre.xyz, r.radii.xyz);
  float depth = puff_optical_depth(chord, r.origin.w, r.dir.w);
  float s0 = clamp(r.origin.w - chord.x, -chord.w, chord.w), s1 = clamp(r.dir.w - chord.x, -chord.w, chord.w);
  float t = chord.w > 0.0 ? chord.x + puff_invert_depth(chord, s0, s1, r.centre.w) : 0.0;
  results[i] = vec4(depth, t, chord.w, chord.x);
}
