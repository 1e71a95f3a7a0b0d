#pragma once
// GPU blocks declared once, for C++ and GLSL alike. A block's fields are written in a shader header
// (`<module>/shaders/<module>/<name>.glsl.h`) as one GLSL struct, which shaders include as they include
// any file and C++ includes inside a namespace that holds the GLSL types below:
//
//   namespace welkin::clouds::gpu_blocks {
//   using namespace welkin::gpu_block_types;
//   #include "clouds/blocks.glsl.h"
//   }
//
// The header holds no #include and no initialisers (GLSL has neither in a struct). The C++ types have
// GLSL's sizes but not its alignments, so the fields come in rows of 16 bytes that std140 and std430
// lay out as C++ does: a vec4, four scalars, a vec3 and then one scalar, or a mat4 (after whole rows);
// a struct the header declares is a whole number of rows, and so is an array's element (no float[N]:
// std140 strides it by 16 bytes).
// A test writes every field from C++ and reads it back in a shader (tests/.../gpu_blocks_test.cpp).
// Value-initialise a block in C++ (`Block b{};`): its fields are then zero, as the padding is.
#include <cstdint>
#include <glm/glm.hpp>

namespace welkin::gpu_block_types {

using vec4 = glm::vec4;
using vec3 = glm::vec3;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
static_assert(sizeof(vec3) == 12 && sizeof(vec4) == 16 && sizeof(mat4) == 64, "GLSL's sizes");

}  // namespace welkin::gpu_block_types
