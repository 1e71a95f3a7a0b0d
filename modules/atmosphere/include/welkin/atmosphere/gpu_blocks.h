#pragma once
// The atmosphere's GPU blocks in C++: the uniform block WelkinAtmosphere (std140) and a star of the
// star catalogue's storage buffer (std430), declared once in shaders/atmosphere/blocks.glsl.h for
// both languages (welkin/gfx/gpu_block.h). Value-initialise them (`FrameBlock u{};`).
#include "welkin/gfx/gpu_block.h"

namespace welkin::atmosphere {

namespace gpu_blocks {
using namespace welkin::gpu_block_types;
#include "atmosphere/blocks.glsl.h"
}  // namespace gpu_blocks
using FrameBlock = gpu_blocks::AtmosphereFrameGpu;
using DensityLayerBlock = gpu_blocks::AtmosphereDensityLayerGpu;
using Star = gpu_blocks::AtmosphereStarGpu;
static_assert(sizeof(FrameBlock) == 848, "FrameBlock: the std140 WelkinAtmosphere block's size");
static_assert(sizeof(DensityLayerBlock) == 32 && sizeof(gpu_blocks::AtmosphereMediumGpu) == 304,
              "whole 16-byte rows: std140 rounds a struct up to them");
static_assert(sizeof(Star) == 32, "Star: the std430 AtmosphereStarGpu struct's size");

}  // namespace welkin::atmosphere
