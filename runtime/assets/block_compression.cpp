// BC1 mip chains: for_each_mip_level makes each level, stb_dxt compresses its blocks (a private,
// static copy, as image_decode.cpp does with stb_image).
#include "welkin/assets/block_compression.h"

#include <algorithm>
#include <cstring>

#define STB_DXT_STATIC
#define STB_DXT_IMPLEMENTATION
#include <stb_dxt.h>

namespace welkin::assets {

namespace {

constexpr size_t kBlockBytes = 8;

size_t blocks_across(int texels) { return size_t(texels + 3) / 4; }

// One level's blocks; texels past the level's edge (levels smaller than 4, odd sizes) repeat the last
// row and column, so they never pull the block's colours away from the texels that are sampled.
void compress_level(const uint8_t* rgba, int w, int h, uint8_t* out) {
  const size_t bw = blocks_across(w), bh = blocks_across(h);
  uint8_t block[16 * 4];
  for (size_t by = 0; by < bh; ++by)
    for (size_t bx = 0; bx < bw; ++bx) {
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
          const size_t sx = std::min<size_t>(bx * 4 + size_t(x), size_t(w) - 1);
          const size_t sy = std::min<size_t>(by * 4 + size_t(y), size_t(h) - 1);
          std::memcpy(block + (y * 4 + x) * 4, rgba + (sy * size_t(w) + sx) * 4, 4);
        }
      stb_compress_dxt_block(out + (by * bw + bx) * kBlockBytes, block, 0, STB_DXT_HIGHQUAL);
    }
}

}  // namespace

Bc1Chain bc1_layout(int width, int height) {
  Bc1Chain chain;
  chain.width = width, chain.height = height;
  size_t offset = 0;
  for (int l = 0; l < mip_level_count(width, height); ++l) {
    const int w = std::max(1, width >> l), h = std::max(1, height >> l);
    const size_t size = blocks_across(w) * blocks_across(h) * kBlockBytes;
    chain.levels.push_back({.width = w, .height = h, .offset = offset, .size = size});
    offset += size;
  }
  return chain;
}

Bc1Chain compress_bc1(const Image& image, bool srgb, MipEdge edge_s, MipEdge edge_t) {
  Bc1Chain chain = bc1_layout(image.width, image.height);
  chain.blocks.resize(chain.levels.back().offset + chain.levels.back().size);
  for_each_mip_level(image, srgb, edge_s, edge_t, [&](int l, int w, int h, const uint8_t* rgba) {
    compress_level(rgba, w, h, chain.blocks.data() + chain.levels[size_t(l)].offset);
  });
  return chain;
}

}  // namespace welkin::assets
