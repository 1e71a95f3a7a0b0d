// The terrain's surface, for its light pass (terrain/light.frag): a glTF metallic-roughness
// material's inputs written per pixel, its own light (emissive) into the frame. Shading once per
// pixel afterwards instead of here: a software rasteriser runs this shader for whole 2x2 quads and
// blocks around triangles of a pixel or two, several times the pixels the terrain covers.
#include "terrain/surface.glsl"
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
layout(location = 0) out vec4 o_emissive;  // masked off while no drawn material has any
layout(location = 1) out uvec4 o_surface;
uniform vec4 u_base_color_factor;
uniform float u_metallic, u_roughness;
uniform vec3 u_emissive;
uniform float u_occlusion_strength;  // glTF: occlusion = 1 + strength (texel - 1)
uniform mat3 u_uv_transform;         // the base colour's texture transform
#if TERRAIN_TEXTURE_TRANSFORMS
// Each other texture's own (only where a drawn material's differ from its base colour's).
uniform mat3 u_metallic_roughness_transform, u_occlusion_transform, u_emissive_transform;
#endif
uniform int u_has_base_color, u_has_metallic_roughness, u_has_occlusion, u_has_emissive;
layout(binding = 0) uniform sampler2D u_base_color;
layout(binding = 1) uniform sampler2D u_metallic_roughness;
layout(binding = 2) uniform sampler2D u_occlusion;
layout(binding = 3) uniform sampler2D u_emissive_map;
void main() {
  vec2 uv = (u_uv_transform * vec3(v_uv, 1.0)).xy;
#if TERRAIN_TEXTURE_TRANSFORMS
  vec2 uv_metallic_roughness = (u_metallic_roughness_transform * vec3(v_uv, 1.0)).xy;
  vec2 uv_occlusion = (u_occlusion_transform * vec3(v_uv, 1.0)).xy,
       uv_emissive = (u_emissive_transform * vec3(v_uv, 1.0)).xy;
#else
  vec2 uv_metallic_roughness = uv, uv_occlusion = uv, uv_emissive = uv;
#endif
  vec4 base = u_base_color_factor;
  if (u_has_base_color == 1) base *= texture(u_base_color, uv);
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_has_metallic_roughness == 1) {
    vec4 mr = texture(u_metallic_roughness, uv_metallic_roughness);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_occlusion == 1)
    occlusion = 1.0 + u_occlusion_strength * (texture(u_occlusion, uv_occlusion).r - 1.0);
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 emissive = u_emissive;
  if (u_has_emissive == 1) emissive *= texture(u_emissive_map, uv_emissive).rgb;
  o_emissive = vec4(emissive, 1.0);
  o_surface =
      terrain_pack_surface(TerrainSurface(base.rgb, occlusion, n, clamp(roughness, 0.03, 1.0), metallic));
}
