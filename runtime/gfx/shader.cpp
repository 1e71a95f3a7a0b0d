#include "welkin/gfx/shader.h"

#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>

#include "welkin/core/error.h"
#include "welkin/core/files.h"

namespace welkin {

GLint Program::location(const std::string& u) const {
  auto it = locations_.find(u);
  if (it != locations_.end()) return it->second;
  GLint loc = glGetUniformLocation(name_.id(), u.c_str());
  locations_[u] = loc;
  return loc;
}
void Program::set(const std::string& u, float v) const { glProgramUniform1f(id(), location(u), v); }
void Program::set(const std::string& u, int v) const { glProgramUniform1i(id(), location(u), v); }
void Program::set(const std::string& u, const glm::vec2& v) const {
  glProgramUniform2fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::vec3& v) const {
  glProgramUniform3fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::vec4& v) const {
  glProgramUniform4fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::ivec2& v) const {
  glProgramUniform2iv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::ivec3& v) const {
  glProgramUniform3iv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::mat3& v) const {
  glProgramUniformMatrix3fv(id(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}

void ShaderLibrary::add_search_dir(const std::filesystem::path& dir, bool front) {
  for (const auto& d : dirs_)
    if (d == dir) return;
  if (front) dirs_.insert(dirs_.begin(), dir);
  else dirs_.push_back(dir);
  cache_.clear();  // an earlier folder may now shadow what a cached program included
}

namespace {
// Generated files are named "<generated>/file" so that they never resolve to a path on disk.
constexpr std::string_view kGeneratedPrefix = "<generated>/";
constexpr uint64_t kMaxShaderFileBytes = 4u << 20;  // one shader source file
}  // namespace

void ShaderLibrary::set_environment(std::map<std::string, std::string> generated_files,
                                    ShaderDefines global_defines, uint64_t version) {
  environment_version_ = version;
  if (generated_files == generated_ && global_defines == global_defines_) return;
  generated_ = std::move(generated_files);
  global_defines_ = std::move(global_defines);
  cache_.clear();
}

std::filesystem::path ShaderLibrary::find(const std::string& file,
                                          const std::filesystem::path& beside) const {
  if (generated_.count(file)) return std::string(kGeneratedPrefix) + file;
  std::error_code ec;
  for (const auto& d : dirs_)
    if (std::filesystem::is_regular_file(d / file, ec)) return d / file;
  if (!beside.empty() && std::filesystem::is_regular_file(beside / file, ec)) return beside / file;
  return {};
}

void ShaderLibrary::expand(const std::filesystem::path& path, ShaderSource& out,
                           std::vector<std::string>& stack, std::vector<std::string>& once) const {
  const std::string name = path.string();
  const bool is_generated = name.rfind(kGeneratedPrefix, 0) == 0;
  std::istringstream in(is_generated ? generated_.at(name.substr(kGeneratedPrefix.size()))
                                     : read_file_text(name, kMaxShaderFileBytes));
  int index = int(out.files.size());
  out.files.push_back(path.string());
  stack.push_back(path.string());
  once.push_back(path.string());
  static const std::regex include_re(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
  std::string line;
  int line_no = 0;
  out.text += "#line 1 " + std::to_string(index) + "\n";
  while (std::getline(in, line)) {
    ++line_no;
    std::smatch m;
    if (std::regex_match(line, m, include_re)) {
      std::filesystem::path inc = find(m[1].str(), path.parent_path());
      if (inc.empty())
        throw Error(ErrorInfo{.file = path.string() + ":" + std::to_string(line_no),
                              .message = "#include \"" + m[1].str() + "\" not found"});
      const bool inc_generated = inc.string().rfind(kGeneratedPrefix, 0) == 0;
      std::string key = inc_generated ? inc.string() : std::filesystem::weakly_canonical(inc).string();
      if (std::find(stack.begin(), stack.end(), inc.string()) != stack.end())
        throw Error(ErrorInfo{.file = path.string() + ":" + std::to_string(line_no),
                              .message = "recursive #include"});
      bool seen = false;
      for (const auto& o : once)
        seen = seen ||
               (o.rfind(kGeneratedPrefix, 0) == 0 ? o : std::filesystem::weakly_canonical(o).string()) == key;
      if (!seen) expand(inc, out, stack, once);  // every include behaves as #pragma once
      out.text += "#line " + std::to_string(line_no + 1) + " " + std::to_string(index) + "\n";
    } else if (line.find("#pragma once") != std::string::npos) {
      out.text += "\n";
    } else {
      out.text += line + "\n";
    }
  }
  stack.pop_back();
}

ShaderSource ShaderLibrary::preprocess(const std::string& file, const ShaderDefines& defines) const {
  std::filesystem::path path = find(file, {});
  if (path.empty()) {
    std::string where;
    for (const auto& d : dirs_) where += (where.empty() ? "" : ", ") + d.string();
    throw Error(ErrorInfo{.file = file, .message = "shader not found (searched: " + where + ")"});
  }
  ShaderSource src;
  src.text = "#version 450 core\n";
  for (const auto& [k, v] : global_defines_) src.text += "#define " + k + " " + v + "\n";
  for (const auto& [k, v] : defines) src.text += "#define " + k + " " + v + "\n";
  std::vector<std::string> stack, once;
  expand(path, src, stack, once);
  return src;
}

namespace {

// Rewrites Mesa's "0:12(5): error: ..." (and NVIDIA's "0(12) : error") to "file.glsl:12:5: error: ...".
std::string map_log(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex mesa(R"((\d+):(\d+)\((\d+)\): (.*))");
  static const std::regex nv(R"((\d+)\((\d+)\) : (.*))");
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, mesa) && std::stoul(m[1]) < files.size())
      out += files[std::stoul(m[1])] + ":" + m[2].str() + ":" + m[3].str() + ": " + m[4].str() + "\n";
    else if (std::regex_search(line, m, nv) && std::stoul(m[1]) < files.size())
      out += files[std::stoul(m[1])] + ":" + m[2].str() + ": " + m[3].str() + "\n";
    else if (!line.empty())
      out += line + "\n";
  }
  return out;
}

}  // namespace

Program link_program(const std::vector<std::pair<GLenum, ShaderSource>>& stages) {
  GLuint prog = glCreateProgram();
  Program program(prog);
  std::vector<GLuint> shaders;
  for (const auto& [stage, src] : stages) {
    GLuint sh = glCreateShader(stage);
    const char* text = src.text.c_str();
    glShaderSource(sh, 1, &text, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint len = 0;
      glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
      std::string log(size_t(std::max(len, 1)), '\0');
      glGetShaderInfoLog(sh, len, nullptr, log.data());
      glDeleteShader(sh);
      for (GLuint s : shaders) glDeleteShader(s);
      std::string mapped = map_log(log.c_str(), src.files);
      throw Error(ErrorInfo{.file = src.files.empty() ? "" : src.files.back(),
                            .message = "shader compile failed:\n" + mapped});
    }
    glAttachShader(prog, sh);
    shaders.push_back(sh);
  }
  glLinkProgram(prog);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetProgramInfoLog(prog, len, nullptr, log.data());
    throw Error(ErrorInfo{.file = stages.empty() ? "" : stages.front().second.files.front(),
                          .message = "shader link failed:\n" + std::string(log.c_str())});
  }
  return program;
}

namespace {
std::string cache_key(const std::vector<std::string>& files, const ShaderDefines& defines) {
  std::string k;
  for (const auto& f : files) k += f + "|";
  for (const auto& [a, b] : defines) k += a + "=" + b + ";";
  return k;
}
}  // namespace

const Program& ShaderLibrary::compute(const std::string& file, const ShaderDefines& defines) {
  auto& slot = cache_[cache_key({file}, defines)];
  if (!slot) slot = std::make_unique<Program>(link_program({{GL_COMPUTE_SHADER, preprocess(file, defines)}}));
  return *slot;
}

const Program& ShaderLibrary::graphics(const std::string& vs, const std::string& fs,
                                       const ShaderDefines& defines) {
  auto& slot = cache_[cache_key({vs, fs}, defines)];
  if (!slot) {
    ShaderDefines vdefs = defines, fdefs = defines;
    vdefs["WELKIN_VERTEX_SHADER"] = "1";
    fdefs["WELKIN_FRAGMENT_SHADER"] = "1";
    slot = std::make_unique<Program>(link_program(
        {{GL_VERTEX_SHADER, preprocess(vs, vdefs)}, {GL_FRAGMENT_SHADER, preprocess(fs, fdefs)}}));
  }
  return *slot;
}

}  // namespace welkin
