// A 3x3 tent over the shafts at their own resolution, across rays that end at similar distances only:
// the per-pixel jitter leaves a pattern of the noise's period that the bilinear upsampling would
// magnify into a checker, while a silhouette (a ridge against the sky) must keep its edge.
layout(location = 0) out vec4 o_loss;
layout(binding = 0) uniform sampler2D u_loss;  // rgb: the shafts, a: where each ray ended (m)
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(u_loss, 0) - 1;
  float end = texelFetch(u_loss, p, 0).a;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec4 s = texelFetch(u_loss, clamp(p + ivec2(x, y), ivec2(0), last), 0);
      float w = float((2 - abs(x)) * (2 - abs(y))) * (abs(s.a - end) <= 0.1 * end ? 1.0 : 0.0);
      sum += w * s.rgb;
      weights += w;
    }
  o_loss = vec4(sum / weights, end);
}
