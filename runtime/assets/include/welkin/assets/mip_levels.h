#pragma once
// A texture's mip levels made on the CPU: each level a box filter of the one before, in linear light
// for sRGB-encoded images, so that every level holds the mean light of level 0 (GL's
// glGenerateMipmap on llvmpipe drifts: +4% in the valley's base colour at 16x16). Made one level at a
// time, so at most two levels are held.
#include <cstdint>
#include <functional>

#include "welkin/assets/model.h"

namespace welkin::assets {

// How the filter reads past an edge: as the texture will be sampled (glTF's wrap modes).
enum class MipEdge { wrap, clamp, mirror };
MipEdge mip_edge_of_gl_wrap(int gl_wrap);  // 10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT

// Sizes as GL makes them: max(1, size >> level), down to 1x1.
inline int mip_level_count(int width, int height) {
  int n = 1;
  while ((width >> (n - 1)) > 1 || (height >> (n - 1)) > 1) ++n;
  return n;
}

// Calls `level(index, width, height, rgba)` for level 0 (the image itself) and each level below.
// `image` must have pixels. Alpha is filtered as a channel of its own, never weighting the colours.
void for_each_mip_level(const Image& image, bool srgb, MipEdge edge_s, MipEdge edge_t,
                        const std::function<void(int, int, int, const uint8_t*)>& level);

}  // namespace welkin::assets
