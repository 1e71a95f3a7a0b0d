#pragma once
// What the god rays' shaders see of a frame: the block declared once in shaders/godrays/blocks.glsl.h
// for C++ and GLSL (welkin/gfx/gpu_block.h).
#include <memory>
#include <string_view>

#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/gpu_block.h"

namespace welkin::godrays {

namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "godrays/blocks.glsl.h"
}  // namespace gpu_blocks
using FrameBlock = gpu_blocks::GodRaysFrameGpu;
static_assert(sizeof(FrameBlock) == 144, "FrameBlock: the std140 GodRaysFrame block's size");
// Where the passes bind it (materials' blocks 0..3 are theirs: the god rays draw no material).
inline constexpr unsigned kFrameBlockBinding = 0;

// The block's buffer, kept by the world.
struct GodRaysGpu {
  static constexpr std::string_view kTypeName = "godrays.GodRaysGpu";
  std::unique_ptr<Buffer> frame;
};

}  // namespace welkin::godrays
