#pragma once
// The default lights' uniform block (std140), declared once in shaders/welkin/default_lights_block.glsl.h
// for both languages (welkin/gfx/gpu_block.h); debug_content.cpp fills it. Included by its path
// from here, so that the runtime's sources keep one include path.
#include "welkin/gfx/gpu_block.h"

namespace welkin {

namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "../shaders/welkin/default_lights_block.glsl.h"
}  // namespace gpu_blocks
using DefaultLightsBlock = gpu_blocks::WelkinDefaultLightsGpu;
static_assert(sizeof(DefaultLightsBlock) == 32,
              "DefaultLightsBlock: the std140 WelkinDefaultLights block's size");

}  // namespace welkin
