// The runtime's GPU block, declared once for C++ and GLSL (shaders/welkin/default_lights_block.glsl.h),
// read back field by field in a shader: every 32-bit word written from C++ (each a distinct float)
// must come back from a std140 uniform block where C++ put it.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "default_lights_block.h"
#include "gpu_block_readback.h"
#include "welkin/core/files.h"
#include "welkin/gfx/gl_context.h"

namespace welkin {
namespace {

TEST(RuntimeGpuBlocks, EveryFieldOfTheDefaultLightsBlockReadsBackFromAStd140UniformBlock) {
  const std::unique_ptr<GlContext> gl = create_headless_context();
  gl->make_current();
  const std::string header =
      read_file_text(WELKIN_SOURCE_DIR "/runtime/shaders/welkin/default_lights_block.glsl.h", 1u << 20);
  std::vector<uint32_t> words(sizeof(DefaultLightsBlock) / 4);
  for (size_t i = 0; i < words.size(); ++i) {
    const float v = 1.5f * float(i + 1);
    std::memcpy(&words[i], &v, 4);
  }
  DefaultLightsBlock block{};
  std::memcpy(static_cast<void*>(&block), words.data(), sizeof(DefaultLightsBlock));
  EXPECT_EQ(welkin::test::read_back_block(header, "WelkinDefaultLightsGpu", &block, sizeof(block), 1, true),
            words);
}

}  // namespace
}  // namespace welkin
