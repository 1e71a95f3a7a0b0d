// Lays the clouds over the frame: the march (at a fraction of the frame's resolution, upsampled
// bilinearly: colour is premultiplied, so filtering it is exact) as colour + transmittance x behind,
// and with CLOUDS_WITH_CLUSTERS the mesh clusters behind it (premultiplied, opacity in alpha):
// march + T (clusters + (1 - opacity) behind), which the blend (one, source alpha) computes. Where
// the temporal resolve ran at the clusters' resolution it has laid them in already (resolve.frag).
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_color;
layout(binding = 0) uniform sampler2D u_clouds;
#if CLOUDS_WITH_CLUSTERS
layout(binding = 1) uniform sampler2D u_clusters;
#endif
void main() {
  vec2 uv = v_ndc * 0.5 + 0.5;
  o_color = texture(u_clouds, uv);
#if CLOUDS_WITH_CLUSTERS
  vec4 c = texture(u_clusters, uv);
  o_color = vec4(o_color.rgb + o_color.a * c.rgb, o_color.a * (1.0 - c.a));
#endif
}
