#pragma once
// Built-in content that needs no module: a gradient backdrop (a test pattern for an empty scene)
// and lit debug shapes (spheres and boxes). Editors and tests use them; they light themselves
// through the light environment's composed material include (welkin/lighting.glsl).
#include <glm/glm.hpp>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin {

struct Backdrop {
  static constexpr std::string_view kTypeName = "core.Backdrop";
  glm::vec3 zenith_color{0.15f, 0.35f, 0.8f};
  glm::vec3 horizon_color{0.7f, 0.8f, 0.95f};
  glm::vec3 ground_color{0.25f, 0.22f, 0.2f};
  float luminance = 8000.0f;  // cd/m^2 of a colour component of 1
  bool grid = true;           // a 10-degree grid, so orientation errors show
};
void describe(TypeBuilder<Backdrop>& t);

// A directional light for the built-in materials (the atmosphere module supplies its own sun).
struct DirectionalLight {
  static constexpr std::string_view kTypeName = "core.DirectionalLight";
  float azimuth_deg = 135.0f;   // clockwise from north
  float elevation_deg = 35.0f;
  glm::vec3 color{1.0f, 0.96f, 0.9f};
  float illuminance_lux = 100000.0f;
  float ambient_fraction = 0.15f;  // sky light as a fraction of the sun's
};
void describe(TypeBuilder<DirectionalLight>& t);

enum class ShapeKind : int { sphere = 0, box = 1 };

struct DebugShape {
  static constexpr std::string_view kTypeName = "core.DebugShape";
  ShapeKind shape = ShapeKind::sphere;
  glm::dvec3 position_m{0.0, 20.0, 2.0};
  glm::vec3 size_m{1.0f, 1.0f, 1.0f};  // radius (sphere: x) or half extents (box)
  glm::vec3 albedo{0.8f, 0.8f, 0.8f};
};
void describe(TypeBuilder<DebugShape>& t);

class ModuleContext;
class Program;
class Registry;
class World;

// Declares the runtime's default light term (the scene's first core.DirectionalLight, or its
// defaults) in the world's light environment; a module's lights of higher priority replace it.
void add_default_light_term(World& world);
// Registers the built-in components and their render systems (part of the "core" module).
void register_debug_content(ModuleContext& ctx);

// Direction (east, north, up) of an azimuth/elevation pair in degrees.
glm::dvec3 direction_from_azimuth_elevation(double azimuth_deg, double elevation_deg);

}  // namespace welkin
