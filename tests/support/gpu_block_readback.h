#pragma once
// Reads a GPU block declared once for C++ and GLSL (welkin/gfx/gpu_block.h) back from a shader: the
// struct's fields are parsed from its header, a compute shader reads each of them (every element of
// an array, every field of a struct the header declares), in declaration order, from the bytes C++
// uploaded and writes their 32-bit words out. C++ lays the fields out
// tightly in declaration order, so the words come back in the order they were written exactly when
// std140 / std430 place every field where C++ does.
#include <epoxy/gl.h>

#include <cstdint>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

#include "welkin/core/error.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/shader.h"

namespace welkin::test {

struct GlslField {
  std::string type, name;
  int count = 1;  // elements: 1, or an array's length
  bool array = false;
};

// The fields of `struct name { ... };` in a GLSL header, in declaration order. A field's type is one of
// GLSL's below or a struct the header declares; a field may be an array (`T name[N];`).
inline std::vector<GlslField> glsl_struct_fields(const std::string& header, const std::string& name) {
  std::smatch body;
  if (!std::regex_search(header, body, std::regex("struct " + name + R"(\s*\{([^}]*)\};)")))
    throw Error("struct " + name + " not found in the block header");
  static const std::regex field(R"(^\s*(\w+)\s+(\w+)\s*(\[\s*(\d+)\s*\])?\s*;)");
  std::vector<GlslField> out;
  const std::string text = std::regex_replace(body[1].str(), std::regex("//[^\n]*"), "");
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    std::smatch m;
    if (std::regex_search(line, m, field))
      out.push_back({m[1].str(), m[2].str(), m[4].matched ? std::stoi(m[4].str()) : 1, m[4].matched});
    else if (line.find_first_not_of(" \t\r") != std::string::npos)
      throw Error("a line of " + name + " this reader does not know: " + line);
  }
  return out;
}

namespace detail {

// 32-bit words in one value of a GLSL type: a basic type, or a struct the header declares.
inline int glsl_type_words(const std::string& header, const std::string& type) {
  if (type == "float" || type == "int" || type == "uint") return 1;
  if (type == "vec3") return 3;
  if (type == "vec4" || type == "ivec4" || type == "uvec4") return 4;
  if (type == "mat4") return 16;
  int words = 0;
  for (const GlslField& f : glsl_struct_fields(header, type))
    words += f.count * glsl_type_words(header, f.type);
  return words;
}

// Shader lines that write every word of `value` (of `type`) to o[], in declaration order.
inline std::string glsl_write_words(const std::string& header, const std::string& type,
                                    const std::string& value) {
  if (type == "float" || type == "int" || type == "uint") return "  o[k++] = w(" + value + ");\n";
  if (type == "mat4")
    return "  for (int c = 0; c < 4; ++c) for (int r = 0; r < 4; ++r) o[k++] = w(" + value + "[c][r]);\n";
  if (type == "vec3" || type == "vec4" || type == "ivec4" || type == "uvec4")
    return "  for (int c = 0; c < " + std::to_string(glsl_type_words(header, type)) + "; ++c) o[k++] = w(" +
           value + "[c]);\n";
  std::string src;
  for (const GlslField& f : glsl_struct_fields(header, type))
    for (int i = 0; i < f.count; ++i)
      src += glsl_write_words(header, f.type,
                              value + "." + f.name + (f.array ? "[" + std::to_string(i) + "]" : ""));
  return src;
}

}  // namespace detail

// Uploads `count` structs `name` (`bytes`, as C++ lays them out) as a std140 uniform block
// (`uniform_block`) or a std430 storage buffer, and returns the words the shader read of each field.
inline std::vector<uint32_t> read_back_block(const std::string& header, const std::string& name,
                                             const void* bytes, size_t size, int count, bool uniform_block) {
  const size_t words = size_t(detail::glsl_type_words(header, name));
  std::string src = "#version 450 core\nlayout(local_size_x = 1) in;\n";
  src += std::regex_replace(header, std::regex(R"(#pragma once)"), "") + "\n";
  src += uniform_block ? "layout(std140, binding = 0) uniform Blocks { " : "layout(std430, binding = 0) readonly buffer Blocks { ";
  src += name + " b[" + std::to_string(count) + "]; };\n";
  src += "layout(std430, binding = 1) writeonly buffer Words { uint o[]; };\n";
  src += "uint w(float v) { return floatBitsToUint(v); }\nuint w(uint v) { return v; }\nuint w(int v) { return uint(v); }\n";
  src += "void main() {\n  uint k = 0u;\n";
  for (int e = 0; e < count; ++e)
    src += detail::glsl_write_words(header, name, "b[" + std::to_string(e) + "]");
  src += "}\n";
  if (words * 4 * size_t(count) != size)
    throw Error(name + ": the header's fields hold " + std::to_string(words * 4) + " bytes, C++'s struct " +
                std::to_string(size / size_t(count)));
  const Program p = link_program({{GL_COMPUTE_SHADER, ShaderSource{src, {name + " readback"}}}});
  // Room (zeros) past the structs: a layout that places fields further than C++ does reads there.
  std::vector<uint8_t> padded(2 * size + 256, 0);
  std::memcpy(padded.data(), bytes, size);
  Buffer in(padded.size(), padded.data());
  Buffer out(words * 4 * size_t(count));
  glBindBufferBase(uniform_block ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER, 0, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
  dispatch_compute(p, 1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> read(words * size_t(count));
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(read.size() * 4), read.data());
  return read;
}

}  // namespace welkin::test
