// A host program's geometry into Welkin's frame: its radiance, and its depth turned into Welkin's
// reversed-Z depth (near / distance along the view axis). Pixels at the host's far-plane depth hold
// no geometry: they keep the sky.
in vec2 v_ndc;
out vec4 o_color;
layout(binding = 0) uniform sampler2D u_host_color;
layout(binding = 1) uniform sampler2D u_host_depth;
uniform int u_forward;        // 1: forward (ndc = 2 depth - 1, far = 1); 0: reversed (ndc = depth, far = 0)
uniform vec2 u_depth_terms;   // distance = y / (ndc + x), from the host's projection
uniform float u_near;         // Welkin's near plane
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float d = texelFetch(u_host_depth, p, 0).r;
  if (u_forward == 1 ? d >= 1.0 : d <= 0.0) discard;
  float ndc = u_forward == 1 ? 2.0 * d - 1.0 : d;
  float distance = u_depth_terms.y / (ndc + u_depth_terms.x);
  gl_FragDepth = clamp(u_near / distance, 0.0, 1.0);
  o_color = vec4(texelFetch(u_host_color, p, 0).rgb, 1.0);
}
