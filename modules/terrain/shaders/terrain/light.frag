// The terrain's light pass: each pixel the terrain covers shaded once, metallic-roughness PBR lit by
// the light environment (welkin/shading.glsl), onto the material's own light where one has any
// (blended) or over what was beneath. Its position comes back from the depth (attached read-only
// and read at the fragment's own texel); aerial perspective is added afterwards over the depth.
#include "welkin/shading.glsl"
#include "terrain/surface.glsl"
in vec2 v_ndc;
out vec4 o_color;
uniform mat4 u_inverse_view_projection;
layout(binding = 0) uniform sampler2D u_depth;
layout(binding = 1) uniform usampler2D u_surface;
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  uvec4 texel = texelFetch(u_surface, px, 0);
  if (texel.w == 0u) discard;  // geometry drawn before the terrain
  TerrainSurface s = terrain_unpack_surface(texel);
  vec4 h = u_inverse_view_projection * vec4(v_ndc, texelFetch(u_depth, px, 0).r, 1.0);
  o_color = vec4(shade_pbr(s.base_color, s.metallic, s.roughness, s.occlusion, s.normal, h.xyz / h.w), 1.0);
}
