#pragma once
// Mip chains in BC1 (S3TC's DXT1), the GPU block format that GL samples without decompressing: 8
// bytes a 4x4 block, 1/8 of RGBA8. Made on the CPU (stb_image_resize for the levels, stb_dxt for the
// blocks) so that the result can be kept on disk and uploaded as it is. Opaque colour only: alpha is
// dropped, which suits the materials that ignore it (terrain).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "welkin/assets/mip_levels.h"

namespace welkin::assets {

struct Bc1Level {
  int width = 0, height = 0;  // in texels, as GL sizes mip levels: max(1, size >> level)
  size_t offset = 0, size = 0;
};

struct Bc1Chain {
  int width = 0, height = 0;
  std::vector<Bc1Level> levels;  // level 0 first, down to 1x1
  std::vector<uint8_t> blocks;   // every level's blocks, each level's rows of blocks top to bottom
};

// The whole chain of `image` (for_each_mip_level; the sRGB encoding kept for the blocks, as GL's sRGB
// BC1 formats decode it), each level compressed. `image` must have pixels.
Bc1Chain compress_bc1(const Image& image, bool srgb, MipEdge edge_s, MipEdge edge_t);

// The layout of a whole chain of that size: levels with their offsets, and no blocks.
Bc1Chain bc1_layout(int width, int height);

}  // namespace welkin::assets
