#pragma once
// Reads a GPU block declared once for C++ and GLSL (welkin/gfx/gpu_block.h) back from a shader: the
// struct's fields are parsed from its header, a compute shader reads each of them, in declaration
// order, from the bytes C++ uploaded and writes their 32-bit words out. C++ lays the fields out
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
  int words = 0;  // 32-bit words
};

// The fields of `struct name { ... };` in a GLSL header, in declaration order.
inline std::vector<GlslField> glsl_struct_fields(const std::string& header, const std::string& name) {
  std::smatch body;
  if (!std::regex_search(header, body, std::regex("struct " + name + R"(\s*\{([^}]*)\};)")))
    throw Error("struct " + name + " not found in the block header");
  static const std::regex field(R"((float|int|uint|vec3|vec4|ivec4|uvec4|mat4)\s+(\w+)\s*;)");
  static const std::regex any_field(R"(^\s*\w+\s+\w+\s*;)");
  std::vector<GlslField> out;
  std::string text = body[1].str();
  std::string line;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    line = text.substr(start, end - start);
    start = end + 1;
    std::smatch m;
    if (std::regex_search(line, m, field)) {
      const std::string t = m[1].str();
      const int words = t == "vec3" ? 3 : t == "mat4" ? 16 : t.find("vec4") != std::string::npos ? 4 : 1;
      out.push_back({t, m[2].str(), words});
    } else if (std::regex_search(line, any_field)) {
      throw Error("a field of " + name + " of a type this reader does not know: " + line);
    }
  }
  return out;
}

// Uploads `count` structs `name` (`bytes`, as C++ lays them out) as a std140 uniform block
// (`uniform_block`) or a std430 storage buffer, and returns the words the shader read of each field.
inline std::vector<uint32_t> read_back_block(const std::string& header, const std::string& name,
                                             const void* bytes, size_t size, int count, bool uniform_block) {
  const std::vector<GlslField> fields = glsl_struct_fields(header, name);
  std::string src = "#version 450 core\nlayout(local_size_x = 1) in;\n";
  src += std::regex_replace(header, std::regex(R"(#pragma once)"), "") + "\n";
  src += uniform_block ? "layout(std140, binding = 0) uniform Blocks { " : "layout(std430, binding = 0) readonly buffer Blocks { ";
  src += name + " b[" + std::to_string(count) + "]; };\n";
  src += "layout(std430, binding = 1) writeonly buffer Words { uint o[]; };\n";
  src += "uint w(float v) { return floatBitsToUint(v); }\nuint w(uint v) { return v; }\nuint w(int v) { return uint(v); }\n";
  src += "void main() {\n  uint k = 0u;\n";
  size_t words = 0;
  for (const GlslField& f : fields) words += size_t(f.words);
  for (int e = 0; e < count; ++e)
    for (const GlslField& f : fields) {
      const std::string v = "b[" + std::to_string(e) + "]." + f.name;
      if (f.words == 1) src += "  o[k++] = w(" + v + ");\n";
      else if (f.words == 16)
        src += "  for (int c = 0; c < 4; ++c) for (int r = 0; r < 4; ++r) o[k++] = w(" + v + "[c][r]);\n";
      else src += "  for (int c = 0; c < " + std::to_string(f.words) + "; ++c) o[k++] = w(" + v + "[c]);\n";
    }
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
