#pragma once
// The terrain's surface at a pixel, between its two passes (terrain.frag writes it, light.frag reads
// it), packed in one RGBA32UI texel: base colour, occlusion, roughness and metallic as 16-bit
// unsigned normalized numbers (glTF keeps them all within [0, 1]), the normal octahedral in two
// 16-bit signed normalized ones (within 5e-5 rad). Roughness is at least 0.03 where the terrain
// wrote: 0 marks no terrain.
struct TerrainSurface {
  vec3 base_color;
  float occlusion;
  vec3 normal;
  float roughness, metallic;
};

uvec4 terrain_pack_surface(TerrainSurface s) {
  vec3 n = s.normal / (abs(s.normal.x) + abs(s.normal.y) + abs(s.normal.z));
  vec2 signs = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  vec2 octahedral = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * signs;
  return uvec4(packUnorm2x16(s.base_color.rg), packUnorm2x16(vec2(s.base_color.b, s.occlusion)),
               packSnorm2x16(octahedral), packUnorm2x16(vec2(s.roughness, s.metallic)));
}

TerrainSurface terrain_unpack_surface(uvec4 t) {
  TerrainSurface s;
  vec2 bo = unpackUnorm2x16(t.y), rm = unpackUnorm2x16(t.w);
  s.base_color = vec3(unpackUnorm2x16(t.x), bo.x);
  s.occlusion = bo.y;
  vec2 e = unpackSnorm2x16(t.z);
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float fold = max(-n.z, 0.0);
  n.xy -= vec2(n.x >= 0.0 ? fold : -fold, n.y >= 0.0 ? fold : -fold);
  s.normal = normalize(n);
  s.roughness = rm.x;
  s.metallic = rm.y;
  return s;
}
