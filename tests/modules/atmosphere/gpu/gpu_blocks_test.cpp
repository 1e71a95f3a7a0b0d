// The atmosphere's GPU blocks, declared once for C++ and GLSL (shaders/atmosphere/blocks.glsl.h), read
// back field by field in a shader: every 32-bit word written from C++ must come back where C++ put it,
// through the nested medium and each element of its density-profile arrays.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "gpu_block_readback.h"
#include "gpu_test_support.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/core/files.h"

namespace welkin::atmosphere {
namespace {

std::string blocks_header() {
  return read_file_text(WELKIN_SOURCE_DIR "/modules/atmosphere/shaders/atmosphere/blocks.glsl.h", 1u << 20);
}

std::vector<uint32_t> words_of(const void* data, size_t size) {
  std::vector<uint32_t> words(size / 4);
  std::memcpy(words.data(), data, size);
  return words;
}

TEST(AtmosphereGpuBlocks, EveryWordOfTheFrameBlockReadsBackFromAStd140UniformBlock) {
  test::gl_context().make_current();
  // Every word a distinct float (the int fields too: their bits come back as they went).
  std::vector<float> words(sizeof(FrameBlock) / 4);
  for (size_t i = 0; i < words.size(); ++i) words[i] = 1.5f * float(i + 1);
  FrameBlock block{};
  std::memcpy(static_cast<void*>(&block), words.data(), sizeof(FrameBlock));
  EXPECT_EQ(welkin::test::read_back_block(blocks_header(), "AtmosphereFrameGpu", &block, sizeof(FrameBlock),
                                          1, true),
            words_of(&block, sizeof(FrameBlock)));
}

TEST(AtmosphereGpuBlocks, EveryWordOfEachStarReadsBackFromAStd430Buffer) {
  test::gl_context().make_current();
  std::vector<Star> stars(3);
  std::vector<float> words(stars.size() * sizeof(Star) / 4);
  for (size_t i = 0; i < words.size(); ++i) words[i] = 1.5f * float(i + 1);
  std::memcpy(static_cast<void*>(stars.data()), words.data(), words.size() * 4);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header(), "AtmosphereStarGpu", stars.data(),
                                          stars.size() * sizeof(Star), 3, false),
            words_of(stars.data(), stars.size() * sizeof(Star)));
}

// The block a frame uploads, made from a scene's atmosphere: the named fields hold what the shaders
// read (the upper Rayleigh layer, the camera's radius, the LUTs' sizes), word for word.
TEST(AtmosphereGpuBlocks, TheBlockOfAFrameReadsBackWithItsNamedFieldsInPlace) {
  test::gl_context().make_current();
  Atmosphere a;
  Camera c;
  c.position_m = {0.0, 0.0, 1500.0};
  const FrameBlock u = make_uniforms(a, nullptr, nullptr, make_frame_view(c, 16, 16));
  ASSERT_EQ(a.rayleigh_density.size(), 1u);
  EXPECT_EQ(u.medium.rayleigh_density[1].exp_scale_per_km, a.rayleigh_density[0].exp_scale_per_km);
  EXPECT_EQ(u.medium.rayleigh_density[0].width_km, 0.0f);  // a one-layer profile: an empty lower layer
  EXPECT_NEAR(u.camera_radius_km, a.bottom_radius_km + 1.5, 1e-3);
  EXPECT_EQ(u.transmittance_width, resolve_quality(a).transmittance_width);
  EXPECT_EQ(
      welkin::test::read_back_block(blocks_header(), "AtmosphereFrameGpu", &u, sizeof(FrameBlock), 1, true),
      words_of(&u, sizeof(FrameBlock)));
}

// The check itself. A struct inside a block takes whole 16-byte rows in std140, so one C++ packs
// into 4 bytes shifts every field after it.
TEST(AtmosphereGpuBlocks, AStructTheShaderPadsReadsBackWrong) {
  test::gl_context().make_current();
  const std::string header = R"(
struct Narrow {
  float a;
};
struct Padded {
  Narrow n;
  float b;
  float c;
  float d;
};
)";
  const float words[4] = {1, 2, 3, 4};
  const std::vector<uint32_t> read =
      welkin::test::read_back_block(header, "Padded", words, sizeof(words), 1, true);
  EXPECT_EQ(read[0], words_of(words, 4)[0]);
  EXPECT_NE(read, words_of(words, sizeof(words)));
}

// And an array of scalars: std140 strides each element to 16 bytes, C++ to 4.
TEST(AtmosphereGpuBlocks, AnArrayTheShaderStridesApartReadsBackWrong) {
  test::gl_context().make_current();
  const std::string header = "struct Strided {\n  float a[4];\n};\n";
  const float words[4] = {1, 2, 3, 4};
  const std::vector<uint32_t> read =
      welkin::test::read_back_block(header, "Strided", words, sizeof(words), 1, true);
  EXPECT_EQ(read[0], words_of(words, 4)[0]);
  EXPECT_NE(read, words_of(words, sizeof(words)));
}

}  // namespace
}  // namespace welkin::atmosphere
