// The terrain's GPU block, declared once for C++ and GLSL (shaders/terrain/cascades_block.glsl.h),
// read back field by field in a shader: every 32-bit word written from C++ (each a distinct float;
// the int's bits come back as they went) must come back from a std140 uniform block where C++ put it,
// through each cascade of its array.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "gpu_block_readback.h"
#include "terrain_gpu.h"
#include "welkin/core/files.h"
#include "welkin/gfx/gl_context.h"

namespace welkin::terrain {
namespace {

TEST(TerrainGpuBlocks, EveryFieldOfTheCascadesBlockReadsBackFromAStd140UniformBlock) {
  const std::unique_ptr<GlContext> gl = create_headless_context();
  gl->make_current();
  const std::string header =
      read_file_text(WELKIN_SOURCE_DIR "/modules/terrain/shaders/terrain/cascades_block.glsl.h", 1u << 20);
  std::vector<uint32_t> words(sizeof(CascadesBlock) / 4);
  for (size_t i = 0; i < words.size(); ++i) {
    const float v = 1.5f * float(i + 1);
    std::memcpy(&words[i], &v, 4);
  }
  CascadesBlock block{};
  std::memcpy(static_cast<void*>(&block), words.data(), sizeof(CascadesBlock));
  EXPECT_EQ(welkin::test::read_back_block(header, "TerrainCascadesGpu", &block, sizeof(block), 1, true), words);
}

}  // namespace
}  // namespace welkin::terrain
