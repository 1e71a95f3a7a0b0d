// BC1 chains, decoded by the GL driver (llvmpipe's S3TC decoder, not Welkin's code): the layout GL
// expects, exact colours where BC1 can hold them, and mip levels filtered in linear light.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cmath>
#include <memory>

#include "welkin/assets/block_compression.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"

namespace welkin::assets::test {
namespace {

class BlockCompression : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { gl_ = create_headless_context().release(); }
  static void TearDownTestSuite() { delete gl_; }
  static GlContext* gl_;
};
GlContext* BlockCompression::gl_ = nullptr;

Image image_of(int w, int h, auto colour) {
  Image img;
  img.width = w, img.height = h;
  img.rgba.resize(size_t(w) * size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::array<uint8_t, 3> c = colour(x, y);
      uint8_t* p = &img.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
  return img;
}

// Every level of the chain uploaded, one read back as RGBA8 (the driver decodes the blocks).
std::vector<uint8_t> decoded_by_gl(const Bc1Chain& chain, bool srgb, int level) {
  const GLenum format = srgb ? GL_COMPRESSED_SRGB_S3TC_DXT1_EXT : GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, GLsizei(chain.levels.size()), format, chain.width, chain.height);
  for (size_t l = 0; l < chain.levels.size(); ++l) {
    const Bc1Level& lv = chain.levels[l];
    glCompressedTextureSubImage2D(id, GLint(l), 0, 0, lv.width, lv.height, format, GLsizei(lv.size),
                                  chain.blocks.data() + lv.offset);
  }
  const Bc1Level& lv = chain.levels[size_t(level)];
  std::vector<uint8_t> out(size_t(lv.width) * size_t(lv.height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(id, level, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
  GLint stored = 0;
  glGetTextureLevelParameteriv(id, level, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &stored);
  EXPECT_EQ(size_t(stored), lv.size) << "the driver keeps the blocks as they are";
  glDeleteTextures(1, &id);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return out;
}

// RGB565 expanded to 8 bits as BC1 decoders do: the colours a block's endpoints hold exactly.
uint8_t expand5(int v) { return uint8_t(v << 3 | v >> 2); }
uint8_t expand6(int v) { return uint8_t(v << 2 | v >> 4); }

TEST(Bc1Layout, HalvesEachLevelDownToOneTexelInWholeBlocks) {
  const Bc1Chain c = bc1_layout(5, 3);
  ASSERT_EQ(c.levels.size(), 3u);
  const int expected[3][4] = {{5, 3, 0, 16}, {2, 1, 16, 8}, {1, 1, 24, 8}};  // width, height, offset, size
  for (size_t l = 0; l < 3; ++l) {
    EXPECT_EQ(c.levels[l].width, expected[l][0]);
    EXPECT_EQ(c.levels[l].height, expected[l][1]);
    EXPECT_EQ(c.levels[l].offset, size_t(expected[l][2]));
    EXPECT_EQ(c.levels[l].size, size_t(expected[l][3]));
  }
  EXPECT_EQ(bc1_layout(4096, 4096).levels.size(), 13u);
  EXPECT_EQ(bc1_layout(4096, 4096).levels.back().offset, 8u * (1024 * 1024 + 512 * 512 + 256 * 256 + 128 * 128 + 64 * 64 + 32 * 32 + 16 * 16 + 64 + 16 + 4 + 1 + 1));
}

// Blocks of one colour each, colours BC1 holds exactly, in sizes that are not a whole number of
// blocks (and smaller than one): every texel comes back exact, so every block sits where GL reads it.
TEST_F(BlockCompression, ColoursItCanHoldComeBackExactInEveryBlock) {
  auto colour = [](int x, int y) {
    const int bx = x / 4, by = y / 4;
    return std::array<uint8_t, 3>{expand5((bx * 7 + by * 3) % 32), expand6((bx * 5 + by * 11) % 64), expand5((bx + by * 13) % 32)};
  };
  for (const auto& [w, h] : {std::pair{37, 22}, {3, 5}, {1, 1}}) {
    const Image img = image_of(w, h, colour);
    const Bc1Chain chain = compress_bc1(img, false, MipEdge::clamp, MipEdge::clamp);
    const std::vector<uint8_t> back = decoded_by_gl(chain, false, 0);
    int worst = 0;
    for (size_t i = 0; i < back.size(); ++i)
      if (i % 4 != 3) worst = std::max(worst, std::abs(int(back[i]) - int(img.rgba[i])));
    EXPECT_EQ(worst, 0) << w << "x" << h;
  }
}

// A checkerboard of black and white texels averages to half the light: 0.5 encodes as sRGB 188 (not
// 128) when the levels are filtered in linear light; a linear texture averages to 128.
TEST_F(BlockCompression, LevelsAverageTheLightNotTheEncoding) {
  const Image img = image_of(16, 8, [](int x, int y) {
    const uint8_t v = (x + y) % 2 ? 255 : 0;
    return std::array<uint8_t, 3>{v, v, v};
  });
  const double srgb_half = 255.0 * (1.055 * std::pow(0.5, 1.0 / 2.4) - 0.055);  // 187.5
  for (const bool srgb : {true, false}) {
    const Bc1Chain chain = compress_bc1(img, srgb, MipEdge::wrap, MipEdge::wrap);
    for (int level = 1; level < int(chain.levels.size()); ++level) {
      // The decoder reads the sRGB blocks as encoded bytes (GL returns the stored encoding for RGBA8).
      const std::vector<uint8_t> back = decoded_by_gl(chain, srgb, level);
      for (size_t i = 0; i < back.size(); ++i) {
        if (i % 4 == 3) continue;
        // Two levels of the 5- or 6-bit endpoints around the value: at most 4.2 apart.
        EXPECT_NEAR(back[i], srgb ? srgb_half : 127.5, 4.3) << "level " << level << (srgb ? " sRGB" : " linear");
      }
    }
  }
}

// A smooth photograph-like field (two gradients and a slow wave): the error BC1 adds stays small.
TEST_F(BlockCompression, SmoothImagesKeepTheirColoursClosely) {
  const Image img = image_of(64, 64, [](int x, int y) {
    return std::array<uint8_t, 3>{uint8_t(60 + x * 2), uint8_t(90 + y * 2), uint8_t(128 + 40 * std::sin(0.1 * (x + y)))};
  });
  const Bc1Chain chain = compress_bc1(img, true, MipEdge::wrap, MipEdge::wrap);
  const double psnr = welkin::image_difference({64, 64, decoded_by_gl(chain, true, 0)}, {64, 64, img.rgba}).psnr_db;
  std::printf("smooth 64x64, BC1: PSNR %.1f dB\n", psnr);
  EXPECT_GT(psnr, 40.0);
}

}  // namespace
}  // namespace welkin::assets::test
