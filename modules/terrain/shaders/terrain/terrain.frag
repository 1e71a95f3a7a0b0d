// Metallic-roughness PBR (glTF) lit by the scene's lights (welkin/lighting.glsl: the atmosphere's
// when present); aerial perspective is added afterwards over the depth buffer.
#include "welkin/shading.glsl"
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
out vec4 o_color;
uniform vec4 u_base_color_factor;
uniform float u_metallic, u_roughness;
uniform vec3 u_emissive;
uniform mat3 u_uv_transform;
uniform int u_has_base_color, u_has_metallic_roughness, u_has_occlusion;
layout(binding = 0) uniform sampler2D u_base_color;
layout(binding = 1) uniform sampler2D u_metallic_roughness;
layout(binding = 2) uniform sampler2D u_occlusion;
layout(binding = 3) uniform sampler2DShadow u_shadow_atlas;  // three cascades side by side
uniform int u_shadows;
uniform mat4 u_cascade[3];
uniform float u_cascade_far[3];
uniform float u_cascade_texel_m[3];

// Fraction of the sun reaching this point: the nearest cascade that covers it, 3x3 hardware-PCF taps.
float sun_visibility(vec3 camera_relative, vec3 normal) {
  if (u_shadows == 0) return 1.0;
  float d = length(camera_relative);
  int c = d < u_cascade_far[0] ? 0 : d < u_cascade_far[1] ? 1 : d < u_cascade_far[2] ? 2 : 3;
  if (c == 3) return 1.0;
  // Normal offset of two texels: a grazing sun on gentle slopes otherwise shadows the surface itself.
  vec4 clip = u_cascade[c] * vec4(camera_relative + normal * 2.0 * u_cascade_texel_m[c], 1.0);
  vec3 p = clip.xyz / clip.w;
  vec2 uv = p.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_atlas, 0));
  float lit = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec2 a = vec2((float(c) + uv.x) / 3.0, uv.y) + vec2(x, y) * texel;
      lit += texture(u_shadow_atlas, vec3(a, p.z));
    }
  return lit / 9.0;
}
void main() {
  vec2 uv = (u_uv_transform * vec3(v_uv, 1.0)).xy;
  vec4 base = u_base_color_factor;
  if (u_has_base_color == 1) base *= texture(u_base_color, uv);
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_has_metallic_roughness == 1) {
    vec4 mr = texture(u_metallic_roughness, uv);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_occlusion == 1) occlusion = texture(u_occlusion, uv).r;
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  o_color = vec4(shade_pbr(base.rgb, metallic, clamp(roughness, 0.03, 1.0), occlusion, n, v_position, sun_visibility(v_position, n)) + u_emissive, 1.0);
}
