// The geometry of the god rays' application.
//   GODRAYS_TILES (shafts without haze): one instanced quad per tile of kTileTexels x kTileTexels
//     texels of the shafts, collapsed where the shafts are zero over everything its pixels' bilinear
//     reads reach: air whose sunlight nothing withholds costs nothing (on a software rasteriser the
//     blending alone costs 0.7 copies of the frame). The result is the full-screen one, bit for bit.
//   otherwise: the full-screen triangle, and what the haze's light needs that is the same for every
//     pixel (the sun's irradiance and the sky's at the camera), found once per vertex.
out vec2 v_ndc;
#if GODRAYS_HAZE
#include "godrays/haze.glsl"
#include "welkin/lighting.glsl"
flat out vec3 v_sun_irradiance;
flat out vec3 v_sky_radiance;  // mean over the sphere of directions: (up + down irradiance) / 4 pi
#endif
#if GODRAYS_TILES
layout(binding = 0) uniform sampler2D u_loss;  // the shafts (non-negative)
const int kTileTexels = GODRAYS_TILE_TEXELS;  // kApplyTileTexels (src/shafts.h)

// Quad corner gl_VertexID (a strip) of tile gl_InstanceID, in [0, 1]^2, or nothing to draw.
bool tile_corner(out vec2 uv) {
  ivec2 size = textureSize(u_loss, 0);
  int across = (size.x + kTileTexels - 1) / kTileTexels;
  vec2 first = vec2(gl_InstanceID % across, gl_InstanceID / across) * float(kTileTexels);
  uv = min((first + vec2(gl_VertexID & 1, gl_VertexID >> 1) * float(kTileTexels)) / vec2(size), vec2(1.0));
  // The tile's pixels read texels first - 1 .. first + kTileTexels; a bilinear read at a corner
  // between four texels is their mean, zero only when all four are (clamped at the edges).
  vec3 sum = vec3(0.0);
  for (int y = 0; y <= kTileTexels; y += 2)
    for (int x = 0; x <= kTileTexels; x += 2)
      sum += textureLod(u_loss, (first + vec2(x, y)) / vec2(size), 0.0).rgb;
  return any(greaterThan(sum, vec3(0.0)));
}
#endif

void main() {
#if GODRAYS_TILES
  vec2 uv;
  bool draw = tile_corner(uv);
  vec2 p = uv * 2.0 - 1.0;
  v_ndc = p;
  gl_Position = draw ? vec4(p, 0.0, 1.0) : vec4(-2.0, -2.0, 0.0, 1.0);  // all four corners: no area
#else
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  v_ndc = p;
#if GODRAYS_HAZE
  v_sun_irradiance = welkin_sun_irradiance(vec3(0.0));
  v_sky_radiance = (welkin_sky_irradiance(gr.up) + welkin_sky_irradiance(-gr.up)) / 12.5663706143592;
#endif
  gl_Position = vec4(p, 0.0, 1.0);
#endif
}
