#include "welkin/gfx/light_environment.h"

#include <algorithm>
#include <cctype>

#include "welkin/core/error.h"
#include "welkin/core/type_id.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/shared_state.h"

namespace welkin {

namespace {
// GL 4.5 guarantees 80 combined texture units and 72 uniform-buffer bindings.
constexpr GLuint kUnitLimit = 80, kBlockLimit = 72;
constexpr const char* kComposedFile = "welkin/lighting.glsl";
}  // namespace

std::string LightEnvironment::macro_name(std::string_view prefix, std::string_view name) {
  std::string m(prefix);
  for (char c : name)
    m +=
        std::isalnum(static_cast<unsigned char>(c)) ? char(std::toupper(static_cast<unsigned char>(c))) : '_';
  return m;
}

void LightEnvironment::add(LightTerm term) {
  if (term.name.empty()) throw Error(ErrorInfo{.expected = "a named light term", .found = "an empty name"});
  auto assign = [&](const std::vector<std::string>& names, std::map<std::string, GLuint, std::less<>>& table,
                    GLuint& next, GLuint limit, const char* what) {
    for (const std::string& n : names) {
      if (table.count(n)) {
        // A replaced term keeps its own bindings; another term's name is a clash.
        bool own = false;
        for (const LightTerm& t : terms_)
          if (t.name == term.name)
            own = own || std::find(t.textures.begin(), t.textures.end(), n) != t.textures.end() ||
                  std::find(t.blocks.begin(), t.blocks.end(), n) != t.blocks.end();
        if (!own)
          throw Error(ErrorInfo{.path = term.name,
                                .expected = std::string("a ") + what + " name no other light term uses",
                                .found = "'" + n + "'"});
        continue;
      }
      if (next >= limit)
        throw Error(
            ErrorInfo{.path = term.name,
                      .expected = std::string("at most ") + std::to_string(limit) + " " + what + "s in all",
                      .found = "more",
                      .message = "the light environment ran out of bindings"});
      table.emplace(n, next++);
    }
  };
  assign(term.textures, units_, next_unit_, kUnitLimit, "texture");
  assign(term.blocks, blocks_, next_block_, kBlockLimit, "uniform block");
  auto it =
      std::find_if(terms_.begin(), terms_.end(), [&](const LightTerm& t) { return t.name == term.name; });
  if (it != terms_.end()) *it = std::move(term);
  else terms_.push_back(std::move(term));
  ++version_;
}

bool LightEnvironment::remove(std::string_view name) {
  auto it = std::find_if(terms_.begin(), terms_.end(), [&](const LightTerm& t) { return t.name == name; });
  if (it == terms_.end()) return false;
  // Bindings stay reserved (they never move), only the term's code and binding go.
  terms_.erase(it);
  ++version_;
  return true;
}

void LightEnvironment::set_moon_lights_surfaces(bool on) {
  if (on == moon_lights_surfaces_) return;
  moon_lights_surfaces_ = on;
  ++version_;
}

bool LightEnvironment::has(std::string_view name) const {
  return std::any_of(terms_.begin(), terms_.end(), [&](const LightTerm& t) { return t.name == name; });
}

std::vector<std::string> LightEnvironment::term_names() const {
  std::vector<std::string> names;
  for (const LightTerm& t : terms_) names.push_back(t.name);
  return names;
}

GLuint LightEnvironment::unit(std::string_view texture) const {
  auto it = units_.find(texture);
  if (it == units_.end())
    throw Error(ErrorInfo{.expected = "a texture declared by a light term",
                          .found = "'" + std::string(texture) + "'"});
  return it->second;
}

GLuint LightEnvironment::block(std::string_view block_name) const {
  auto it = blocks_.find(block_name);
  if (it == blocks_.end())
    throw Error(ErrorInfo{.expected = "a uniform block declared by a light term",
                          .found = "'" + std::string(block_name) + "'"});
  return it->second;
}

ShaderDefines LightEnvironment::binding_defines() const {
  ShaderDefines d;
  for (const auto& [n, u] : units_) d[macro_name("WELKIN_UNIT_", n)] = std::to_string(u);
  for (const auto& [n, b] : blocks_) d[macro_name("WELKIN_BLOCK_", n)] = std::to_string(b);
  return d;
}

std::string LightEnvironment::composed_source() const {
  std::string s =
      "#pragma once\n// Composed by the runtime's light environment (welkin/gfx/light_environment.h) from "
      "the terms:";
  for (const LightTerm& t : terms_) s += " " + t.name;
  s += "\n";
  s += std::string("#define WELKIN_MOON_LIGHT ") + (moon_lights_surfaces_ ? "1" : "0") + "\n";
  const LightTerm* lights = nullptr;
  const LightTerm* aerial = nullptr;
  const LightTerm* medium = nullptr;
  for (const LightTerm& t : terms_) {
    if (!t.lights.empty() && (!lights || t.priority > lights->priority)) lights = &t;
    if (!t.aerial_perspective.empty() && (!aerial || t.priority > aerial->priority)) aerial = &t;
    if (!t.medium.empty() && (!medium || t.priority > medium->priority)) medium = &t;
  }
  // The light functions are declared first, so that terms may use them.
  s += "vec3 welkin_sun_direction();\nvec3 welkin_sun_irradiance(vec3 p);\nvec3 welkin_moon_direction();\n"
       "vec3 welkin_moon_irradiance(vec3 p);\nvec3 welkin_sky_irradiance(vec3 n);\n";
  s += "// What reaches a surface point (welkin_surface_light): the sun's irradiance there, the fraction of "
       "each\n"
       "// light and of the sky's light reaching it, and the irradiance the terms redirect onto it.\n"
       "struct WelkinSurfaceLight {\n  vec3 sun_irradiance;\n  float sun_visibility, moon_visibility, "
       "sky_visibility;\n"
       "  vec3 added_irradiance;\n};\n";
  // Only the terms whose functions are called are included: an unused provider compiles nothing.
  for (const LightTerm& t : terms_) {
    bool used = &t == lights || &t == aerial || &t == medium || !t.light_visibility.empty() ||
                !t.sky_visibility.empty() || !t.added_irradiance.empty() || !t.surface_light.empty();
    if (used && !t.include.empty()) s += "#include \"" + t.include + "\"\n";
  }
  if (lights) {
    const std::string& p = lights->lights;
    s += "vec3 welkin_sun_direction() { return " + p + "_sun_direction(); }\n";
    s += "vec3 welkin_sun_irradiance(vec3 p) { return " + p + "_sun_irradiance(p); }\n";
    s += "vec3 welkin_moon_direction() { return " + p + "_moon_direction(); }\n";
    s += "vec3 welkin_moon_irradiance(vec3 p) { return " + p + "_moon_irradiance(p); }\n";
    s += "vec3 welkin_sky_irradiance(vec3 n) { return " + p + "_sky_irradiance(n); }\n";
  } else {
    s += "vec3 welkin_sun_direction() { return vec3(0.0, 0.0, 1.0); }\n";
    s += "vec3 welkin_sun_irradiance(vec3 p) { return vec3(0.0); }\n";
    s += "vec3 welkin_moon_direction() { return vec3(0.0, 0.0, 1.0); }\n";
    s += "vec3 welkin_moon_irradiance(vec3 p) { return vec3(0.0); }\n";
    s += "vec3 welkin_sky_irradiance(vec3 n) { return vec3(0.0); }\n";
  }
  // Functions that fold every term's contribution into one value: `variable` starts as `declaration`
  // and each term applies `op` (a product or a sum).
  auto fold = [&](const std::string& comment, const std::string& head, const std::string& declaration,
                  const std::string& variable, const std::string& op, const std::string& args,
                  std::string LightTerm::*function) {
    s += "// " + comment + "\n" + head + " {\n  " + declaration + ";\n";
    for (const LightTerm& t : terms_)
      if (!(t.*function).empty()) s += "  " + variable + " " + op + " " + t.*function + "(" + args + ");\n";
    s += "  return " + variable + ";\n}\n";
  };
  fold("Fraction of light 0 (sun) or 1 (moon) reaching a camera-relative point with normal n.",
       "float welkin_light_visibility(vec3 p, vec3 n, int light)", "float v = 1.0", "v", "*=", "p, n, light",
       &LightTerm::light_visibility);
  fold("Fraction of the sky's light reaching the point.", "float welkin_sky_visibility(vec3 p, vec3 n)",
       "float v = 1.0", "v", "*=", "p, n", &LightTerm::sky_visibility);
  fold("Diffuse irradiance the terms redirect onto the point.",
       "vec3 welkin_added_irradiance(vec3 p, vec3 n)", "vec3 e = vec3(0.0)", "e", "+=", "p, n",
       &LightTerm::added_irradiance);
  // Everything at once for a surface point: each term's shared work done once.
  s += "WelkinSurfaceLight welkin_surface_light(vec3 p, vec3 n) {\n"
       "  WelkinSurfaceLight l = WelkinSurfaceLight(welkin_sun_irradiance(p), 1.0, 1.0, 1.0, vec3(0.0));\n";
  for (const LightTerm& t : terms_) {
    if (!t.surface_light.empty()) {
      s += "  " + t.surface_light + "(p, n, l);\n";
      continue;
    }
    if (!t.light_visibility.empty())
      s += "  l.sun_visibility *= " + t.light_visibility +
           "(p, n, 0);\n#if WELKIN_MOON_LIGHT\n  l.moon_visibility *= " + t.light_visibility +
           "(p, n, 1);\n#endif\n";
    if (!t.sky_visibility.empty()) s += "  l.sky_visibility *= " + t.sky_visibility + "(p, n);\n";
    if (!t.added_irradiance.empty()) s += "  l.added_irradiance += " + t.added_irradiance + "(p, n);\n";
  }
  s += "  return l;\n}\n";
  s += "// Light added between a camera-relative point and the camera, and that path's transmittance.\n";
  if (aerial)
    s += "vec3 welkin_aerial_perspective(vec3 p, out vec3 transmittance) { return " +
         aerial->aerial_perspective + "(p, transmittance); }\n";
  else
    s += "vec3 welkin_aerial_perspective(vec3 p, out vec3 transmittance) { transmittance = vec3(1.0); return "
         "vec3(0.0); }\n";
  s += "// Light of unit irradiance the medium at p scatters back along view_dir (1/(m sr)), and its "
       "extinction (1/m).\n";
  if (medium)
    s += "vec3 welkin_medium_scattering(vec3 p, vec3 view_dir, int light, out vec3 extinction) { return " +
         medium->medium + "(p, view_dir, light, extinction); }\n";
  else
    s += "vec3 welkin_medium_scattering(vec3 p, vec3 view_dir, int light, out vec3 extinction) { extinction "
         "= vec3(0.0); "
         "return vec3(0.0); }\n";
  return s;
}

void LightEnvironment::bind_block(std::string_view block_name, std::unique_ptr<Buffer>& buffer,
                                  const void* data, size_t bytes) const {
  if (!buffer || buffer->size() != bytes) buffer = std::make_unique<Buffer>(bytes);
  buffer->upload(data, bytes);
  glBindBufferBase(GL_UNIFORM_BUFFER, block(block_name), buffer->id());
}

bool LightEnvironment::shades_surfaces() const {
  for (const LightTerm& t : terms_)
    if (!t.light_visibility.empty() || !t.sky_visibility.empty() || !t.added_irradiance.empty() ||
        !t.surface_light.empty())
      return true;
  return false;
}

std::optional<uint64_t> LightEnvironment::state() const {
  uint64_t h = fnv1a_64_of(version_);
  for (const LightTerm& t : terms_) {
    if (!t.state) return std::nullopt;
    h = fnv1a_64_of(t.state(), h);
  }
  return h;
}

void LightEnvironment::bind() const {
  for (const LightTerm& t : terms_)
    if (t.bind) t.bind(*this);
}

void LightEnvironment::install(ShaderLibrary& shaders) const {
  if (shaders.environment_version() == version_) return;
  shaders.set_environment({{kComposedFile, composed_source()}}, binding_defines(), version_);
}

std::optional<glm::vec3> scene_sun_direction(World& world) {
  const LightSources* lights = world.find_resource<LightSources>();
  if (lights && lights->scene.sun.present) return glm::vec3(lights->scene.sun.direction());
  const Entity light = world.registry().first<DirectionalLight>();
  if (light.is_null()) return std::nullopt;
  const DirectionalLight& l = *world.registry().get<DirectionalLight>(light);
  return glm::vec3(direction_from_azimuth_elevation(l.azimuth_deg, l.elevation_deg));
}

}  // namespace welkin
