#pragma once
// The light a material receives, composed from the terms of the loaded modules. A module declares a
// term (its GLSL include, the functions it contributes, the textures and uniform blocks it needs and
// how to bind them); the runtime assigns texture units and block bindings, writes the composed
// `welkin/lighting.glsl` that materials include, and binds every term before a material draws. No
// module owns the file or a binding by convention, and a term that is not declared is not compiled.
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/shader.h"

namespace welkin {

class LightEnvironment;

// One module's contribution. Function names are GLSL functions its include defines.
struct LightTerm {
  std::string name;     // unique, e.g. "atmosphere", "terrain.cascades", "clouds.shadows"
  std::string include;  // GLSL file defining the term's functions, e.g. "atmosphere/light_term.glsl"
  // Prefix P of the light sources: P_sun_direction(), P_sun_irradiance(vec3 p), P_moon_direction(),
  // P_moon_irradiance(vec3 p), P_sky_irradiance(vec3 n). The term with the highest `priority` that
  // provides lights wins; the runtime's default lights have priority 0.
  std::string lights;
  int priority = 0;
  // float F(vec3 p, vec3 n, int light): fraction of light 0 (sun) or 1 (moon) reaching p; multiplied.
  std::string light_visibility;
  // float F(vec3 p, vec3 n): fraction of the sky's light reaching p; multiplied.
  std::string sky_visibility;
  // vec3 F(vec3 p, vec3 n): diffuse irradiance a term redirects onto p (sunlight a cloud deck
  // scatters down, say); summed. Terms may call the composed welkin_* light functions.
  std::string added_irradiance;
  // void F(vec3 p, vec3 n, inout WelkinSurfaceLight light): the three above together at a surface
  // point, for a term whose three share their work (one shadow-map lookup): welkin_surface_light,
  // what materials call, then does that work once per point instead of once per function (shader
  // compilers do not merge the repeated lookups, and a software rasteriser pays for each). It
  // multiplies the visibilities and adds to the added irradiance as the three would; `light` holds
  // the sun's irradiance at p. A term without it is asked through its three functions.
  std::string surface_light;
  // vec3 F(vec3 p, out vec3 transmittance): light added between p and the camera, and the
  // transmittance of that path (one provider; materials that write no depth call it).
  std::string aerial_perspective;
  // vec3 F(vec3 p, vec3 view_dir, int light, out vec3 extinction): light of unit irradiance from light
  // 0 (sun) or 1 (moon) that the medium at p scatters back along view_dir (the camera's ray), per
  // metre (scattering coefficient x phase, 1/(m sr)), and the medium's extinction (1/m); one
  // provider (the highest priority). What volumetric shadowing of the air (god rays) integrates.
  std::string medium;
  std::vector<std::string> textures;  // names; each gets a unit: #define WELKIN_UNIT_<NAME>
  std::vector<std::string> blocks;    // names; each gets a binding: #define WELKIN_BLOCK_<NAME>
  // Binds the term's textures and blocks at the units the environment assigned.
  std::function<void(const LightEnvironment&)> bind;
  // A digest of everything the term's functions read this frame (its blocks' bytes, which builds of
  // its textures), known once the frame's render systems before the caller have recorded their
  // passes. What reads the light may be kept from an earlier frame while the digest holds; a term
  // without one changes every frame.
  std::function<uint64_t()> state;
};

class LightEnvironment {
 public:
  static constexpr std::string_view kTypeName = "core.LightEnvironment";
  // First unit and binding handed out: materials keep units 0..7 and blocks 0..3 for themselves.
  static constexpr GLuint kFirstUnit = 8, kFirstBlock = 4;

  // Adds a term or replaces the one of the same name. Units and bindings once assigned never move.
  // Throws Error on a name clash of textures/blocks or when the units run out.
  void add(LightTerm term);
  bool remove(std::string_view name);
  bool has(std::string_view name) const;
  // Whether any term shadows or adds to the light a surface receives (visibility or added light):
  // surfaces drawn without a material (the atmosphere's ground) need these terms only then.
  bool shades_surfaces() const;
  std::vector<std::string> term_names() const;

  // The unit or binding assigned to a texture or block name; throws Error when unknown.
  GLuint unit(std::string_view texture) const;
  GLuint block(std::string_view block_name) const;

  // The composed welkin/lighting.glsl, and the #defines of every assigned unit and binding.
  std::string composed_source() const;
  ShaderDefines binding_defines() const;
  // The first texture unit the environment has not handed out: a material needing more than units
  // 0..7 takes units from here (they stay free until a term is added).
  GLuint free_unit() const { return next_unit_; }
  // Whether the second light (the moon) reaches surfaces. The provider of the lights clears it where
  // that light is negligible (the moon by day): every material then compiles without its terms
  // (`#define WELKIN_MOON_LIGHT 0` in the composed file), which halves the direct light's cost.
  void set_moon_lights_surfaces(bool on);
  bool moon_lights_surfaces() const { return moon_lights_surfaces_; }
  // Bumped whenever the composed source or the bindings change.
  uint64_t version() const { return version_; }

  // The digest of every term's state, or nothing when a term has none (then nothing that reads the
  // light can be kept between frames).
  std::optional<uint64_t> state() const;
  // Binds every term's resources: call in a material pass before drawing.
  void bind() const;
  // For a term's bind: uploads `bytes` of a std140 block into `buffer` (made on first use) and binds it
  // at the block's binding.
  void bind_block(std::string_view block_name, std::unique_ptr<Buffer>& buffer, const void* data,
                  size_t bytes) const;
  // Installs the composed file and the binding defines into a shader library (cheap when unchanged).
  void install(ShaderLibrary& shaders) const;

  static std::string macro_name(std::string_view prefix, std::string_view name);

 private:
  std::vector<LightTerm> terms_;  // in the order they were added
  std::map<std::string, GLuint, std::less<>> units_, blocks_;
  GLuint next_unit_ = kFirstUnit, next_block_ = kFirstBlock;
  uint64_t version_ = 1;
  bool moon_lights_surfaces_ = true;
};

class World;
// Direction toward the scene's sun (the shared LightSources' scene sun, else the first
// core.DirectionalLight), also below the horizon; nullopt when the scene has neither.
std::optional<glm::vec3> scene_sun_direction(World& world);

}  // namespace welkin
