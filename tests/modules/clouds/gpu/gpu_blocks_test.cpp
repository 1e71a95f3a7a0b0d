// The clouds' GPU blocks, declared once for C++ and GLSL (shaders/clouds/blocks.glsl.h), read back
// field by field in a shader: every 32-bit word written from C++ must come back where C++ put it.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "clouds_test_support.h"
#include "gpu_block_readback.h"
#include "welkin/core/files.h"

namespace welkin::clouds {
namespace {

std::string blocks_header(const std::string& name = "blocks") {
  return read_file_text(WELKIN_SOURCE_DIR "/modules/clouds/shaders/clouds/" + name + ".glsl.h", 1u << 20);
}

// `count` structs whose every word holds a distinct float.
template <class T>
std::vector<T> distinct_words(int count) {
  std::vector<T> blocks(static_cast<size_t>(count));
  std::vector<float> words(blocks.size() * sizeof(T) / 4);
  for (size_t i = 0; i < words.size(); ++i) words[i] = 1.5f * float(i + 1);
  std::memcpy(static_cast<void*>(blocks.data()), words.data(), words.size() * 4);
  return blocks;
}

std::vector<uint32_t> words_of(const void* data, size_t size) {
  std::vector<uint32_t> words(size / 4);
  std::memcpy(words.data(), data, size);
  return words;
}

TEST(CloudsGpuBlocks, EveryFieldOfTheFrameBlockReadsBackFromAStd140UniformBlock) {
  test::gl_context().make_current();
  const std::vector<FrameBlock> frame = distinct_words<FrameBlock>(1);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header(), "CloudsFrameGpu", frame.data(), sizeof(FrameBlock), 1, true),
            words_of(frame.data(), sizeof(FrameBlock)));
}

TEST(CloudsGpuBlocks, EveryFieldOfEachLayerReadsBackFromAStd430Buffer) {
  test::gl_context().make_current();
  const std::vector<LayerBlock> layers = distinct_words<LayerBlock>(3);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header(), "CloudLayerGpu", layers.data(), 3 * sizeof(LayerBlock), 3, false),
            words_of(layers.data(), 3 * sizeof(LayerBlock)));
}

TEST(CloudsGpuBlocks, EveryFieldOfEachClusterPuffReadsBackFromAStd430Buffer) {
  test::gl_context().make_current();
  const std::vector<ClusterPuffGpu> puffs = distinct_words<ClusterPuffGpu>(3);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header("puff_block"), "ClusterPuff", puffs.data(), 3 * sizeof(ClusterPuffGpu), 3, false),
            words_of(puffs.data(), 3 * sizeof(ClusterPuffGpu)));
}

TEST(CloudsGpuBlocks, EveryFieldOfEachBillboardReadsBackFromAStd430Buffer) {
  test::gl_context().make_current();
  const std::vector<BillboardGpu> billboards = distinct_words<BillboardGpu>(3);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header("billboard_block"), "Billboard", billboards.data(), 3 * sizeof(BillboardGpu), 3, false),
            words_of(billboards.data(), 3 * sizeof(BillboardGpu)));
}

TEST(CloudsGpuBlocks, EveryFieldOfTheShadowBlockReadsBackFromAStd140UniformBlock) {
  test::gl_context().make_current();
  const std::vector<ShadowBlock> shadow = distinct_words<ShadowBlock>(1);
  EXPECT_EQ(welkin::test::read_back_block(blocks_header("shadow_block"), "CloudsShadowGpu", shadow.data(), sizeof(ShadowBlock), 1, true),
            words_of(shadow.data(), sizeof(ShadowBlock)));
}

// The check itself: a struct C++ packs tightly but std430 pads (a vec3 after a scalar starts on 16
// bytes) reads back shifted.
TEST(CloudsGpuBlocks, AFieldTheShaderPlacesElsewhereReadsBackWrong) {
  test::gl_context().make_current();
  const std::string header = "struct Skewed {\n  float a;\n  vec3 b;\n  float c;\n  float d;\n  float e;\n  float f;\n};\n";
  const float words[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<uint32_t> read = welkin::test::read_back_block(header, "Skewed", words, sizeof(words), 1, false);
  EXPECT_EQ(read[0], words_of(words, 4)[0]);
  EXPECT_NE(read, words_of(words, sizeof(words)));
}

}  // namespace
}  // namespace welkin::clouds
