#pragma once
// Shader programs loaded from .glsl files with `#include "file"` (resolved along the search path,
// then beside the including file) and per-permutation defines. Module folders are searched before
// the runtime's, so a module overrides a shared include such as welkin/lighting.glsl. The `#version` line is
// prepended at load; compile errors are reported with the real file and line.
#include <filesystem>
#include <glm/glm.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "welkin/gfx/gl_objects.h"

namespace welkin {

using ShaderDefines = std::map<std::string, std::string>;

class Program {
 public:
  Program() = default;
  explicit Program(GLuint id) : name_(id) {}
  GLuint id() const { return name_.id(); }
  void use() const { glUseProgram(name_.id()); }
  GLint location(const std::string& uniform) const;
  void set(const std::string& u, float v) const;
  void set(const std::string& u, int v) const;
  void set(const std::string& u, const glm::vec2& v) const;
  void set(const std::string& u, const glm::vec3& v) const;
  void set(const std::string& u, const glm::vec4& v) const;
  void set(const std::string& u, const glm::ivec2& v) const;
  void set(const std::string& u, const glm::ivec3& v) const;
  void set(const std::string& u, const glm::mat3& v) const;
  void set(const std::string& u, const glm::mat4& v) const;

 private:
  GlProgramName name_;
  mutable std::unordered_map<std::string, GLint> locations_;
};

// The preprocessed source of one shader stage and the files each source-string number stands for.
struct ShaderSource {
  std::string text;
  std::vector<std::string> files;
};

class ShaderLibrary {
 public:
  // Appends a folder; `front` puts it before all others (modules override the runtime).
  void add_search_dir(const std::filesystem::path& dir, bool front = false);
  const std::vector<std::filesystem::path>& search_dirs() const { return dirs_; }

  // Preprocesses a stage (includes expanded, #version and defines prepended). Throws Error.
  ShaderSource preprocess(const std::string& file, const ShaderDefines& defines) const;
  // Compiled and linked programs, cached by files and defines.
  const Program& compute(const std::string& file, const ShaderDefines& defines = {});
  const Program& graphics(const std::string& vertex_file, const std::string& fragment_file,
                          const ShaderDefines& defines = {});
  size_t cached_programs() const { return cache_.size(); }

  // Generated files (found before any folder, by name) and defines prepended to every stage: the
  // light environment's composed lighting and its bindings. Drops cached programs when they change.
  void set_environment(std::map<std::string, std::string> generated_files, ShaderDefines global_defines,
                       uint64_t version);
  uint64_t environment_version() const { return environment_version_; }

 private:
  std::filesystem::path find(const std::string& file, const std::filesystem::path& beside) const;
  void expand(const std::filesystem::path& path, ShaderSource& out, std::vector<std::string>& stack,
              std::vector<std::string>& once) const;
  std::vector<std::filesystem::path> dirs_;
  std::map<std::string, std::unique_ptr<Program>> cache_;
  std::map<std::string, std::string> generated_;
  ShaderDefines global_defines_;
  uint64_t environment_version_ = 0;
};

// Compiles and links stage sources; throws Error with file:line messages on failure.
Program link_program(const std::vector<std::pair<GLenum, ShaderSource>>& stages);

}  // namespace welkin
