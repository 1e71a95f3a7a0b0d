#pragma once
// What several modules share about a scene, as typed world resources (Bevy's plugin resources):
// the planet and the scene's place on it, the sun and the moon, the clock. The runtime declares
// them and clears them at the start of every update; during the update phase their owners write
// them (the time of day first, in Stage::simulate, then the modules that complete them, in
// Stage::complete_shared_state), and everything after reads them. No module names another's components.
//
//   resource      written by                      read by
//   PlanetFrame   atmosphere (the planet),        runtime (painted maps), clouds, terrain, god rays
//                 time of day (the origin)
//   LightSources  time of day (the ephemeris),    atmosphere, runtime (light environment, default
//                 atmosphere (its sun and moon)   light), clouds, terrain, god rays
//   SceneTime     time of day                     atmosphere (stars), clouds (wind)
//
// A module that reads what only another module writes lists that module in its manifest
// ("depends" when it cannot work without it, "uses" when it reads it only if the scene has it).
#include <glm/glm.hpp>
#include <optional>
#include <string_view>

namespace welkin {

class World;

// The scene origin's place on Earth.
struct GeodeticPlace {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;  // east positive
  double elevation_m = 0.0;
};

// The planet the scene stands on, in the scene frame (x east, y north, z up at the origin, metres).
// Without a module to say otherwise: Earth's 6360 km, its centre straight below the origin.
struct PlanetFrame {
  static constexpr std::string_view kTypeName = "core.PlanetFrame";
  bool from_scene = false;  // a module set the planet (else the default Earth below)
  glm::dvec3 center_m{0.0, 0.0, -6360000.0};
  double radius_m = 6360000.0;
  std::optional<double> atmosphere_top_m;  // radius of the top of the air, when the scene has air
  std::optional<GeodeticPlace> origin;     // where the origin is on Earth, when the scene knows it
};

// A light of the sky seen from the scene origin. Illuminance is outside the atmosphere, on a plane
// facing the light.
struct LightSource {
  bool present = false;
  double azimuth_deg = 0.0;  // clockwise from north
  double elevation_deg = 0.0;
  double illuminance_lux = 0.0;  // unobscured (the sun without an eclipse)
  double angular_radius_deg = 0.0;
  double visible_fraction = 1.0;      // of the disc's light not eclipsed
  double illuminated_fraction = 1.0;  // of the disc lit (the moon's phase)

  // Toward the light (east, north, up).
  glm::dvec3 direction() const;
};

struct SunAndMoon {
  LightSource sun, moon;
};

struct LightSources {
  static constexpr std::string_view kTypeName = "core.LightSources";
  // Where the sun and the moon stand at the scene's date and place (the time of day's ephemeris).
  SunAndMoon ephemeris;
  // The sun and the moon as the scene draws them (the atmosphere, from its own lights, which follow
  // the ephemeris when there is one); absent when the scene has no such light.
  SunAndMoon scene;
};

// The scene's clock, when it has one (the time of day).
struct SceneTime {
  static constexpr std::string_view kTypeName = "core.SceneTime";
  bool present = false;
  double local_time_h = 0.0;  // local clock time, hours in [0, 24)
  double julian_day = 0.0;    // UT
  double local_sidereal_time_deg = 0.0;
};

// Resets every shared resource to "nothing written" (World::update calls it first).
void clear_shared_state(World& world);

}  // namespace welkin
