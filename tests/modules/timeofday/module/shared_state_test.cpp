// The world's shared state (welkin/scene/shared_state.h) between real modules: the time of day
// writes the ephemeris, the clock and the origin; the atmosphere completes the lights it draws and
// its planet; the runtime reads them. And the modules' manifests, as the loader checks them.
#include "welkin/scene/shared_state.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/stars.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/scene/painted_map.h"
#include "welkin/scene/scene_file.h"
#include "welkin/timeofday/components.h"
#include "welkin/timeofday/sky.h"

namespace welkin::modules {
const ModuleDefinition& timeofday_module();
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& godrays_module();
}  // namespace welkin::modules

namespace {

using namespace welkin;
using nlohmann::json;

// Reda & Andreas 2004, table A5.1 (the SPA's worked example): topocentric zenith 50.11162,
// azimuth 194.34024 at Golden, Colorado, 2003-10-17 12:30:30 local time.
const json kSpaExample = {{"year", 2003},
                          {"month", 10},
                          {"day", 17},
                          {"local_time_h", 12.0 + 30.0 / 60 + 30.0 / 3600},
                          {"utc_offset_h", -7},
                          {"latitude_deg", 39.742476},
                          {"longitude_deg", -105.1786},
                          {"elevation_m", 1830.14},
                          {"pressure_mbar", 820},
                          {"temperature_c", 11},
                          {"delta_t_mode", "manual"},
                          {"delta_t_s", 67}};

json entity(const std::string& name, const json& components) {
  return {{"name", name}, {"components", components}};
}

// A world of the given static modules (in that order) and entities.
std::unique_ptr<World> make_world(const std::vector<const ModuleDefinition*>& modules, const json& entities) {
  auto w = std::make_unique<World>();
  for (const ModuleDefinition* m : modules) w->modules().add_static(*m);
  load_scene(*w, json{{"welkin_scene", 1}, {"entities", entities}}, "shared.json");
  return w;
}

// The same instant computed straight from the ephemeris library, not through the module.
timeofday::SkyState spa_example_sky() {
  const timeofday::Observer observer{.latitude_deg = 39.742476,
                                     .longitude_deg = -105.1786,
                                     .elevation_m = 1830.14,
                                     .pressure_mbar = 820,
                                     .temperature_c = 11};
  const auto utc = timeofday::UtcTime::from_civil(2003, 10, 17, 12, 30, 30.0, -7 * 60);
  return timeofday::compute_sky(observer, utc, {.delta_t_s = 67.0});
}

template <class T>
T& first(World& w) {
  return *w.registry().get<T>(w.registry().first<T>());
}

TEST(SharedState, TheTimeOfDaysSunIsTheOneTheAtmosphereDrawsAndTheLightsRead) {
  const json atmosphere = {{"bottom_radius_km", 3000.0},
                           {"top_radius_km", 3080.0},
                           {"planet_center_below_origin", false},
                           {"planet_center_m", {10.0, -20.0, -3000500.0}}};
  // The atmosphere loads before the time of day: the order of the systems, not of the modules,
  // puts the ephemeris before the lights that follow it.
  auto w = make_world({&modules::atmosphere_module(), &modules::timeofday_module()},
                      json::array({entity("air", {{"atmosphere.Atmosphere", atmosphere},
                                                  {"atmosphere.Sun", json::object()},
                                                  {"atmosphere.Moon", json::object()},
                                                  {"atmosphere.Stars", json::object()}}),
                                   entity("clock", {{"timeofday.TimeOfDay", kSpaExample}})}));
  w->update({});
  const timeofday::SkyState sky = spa_example_sky();
  const LightSources& lights = w->resource<LightSources>();
  ASSERT_TRUE(lights.ephemeris.sun.present);
  EXPECT_NEAR(lights.ephemeris.sun.azimuth_deg, 194.34024, 1e-4);
  EXPECT_NEAR(90.0 - lights.ephemeris.sun.elevation_deg, 50.11162, 1e-4);
  EXPECT_NEAR(lights.ephemeris.sun.azimuth_deg, sky.sun.azimuth_deg, 1e-9);
  EXPECT_NEAR(lights.ephemeris.sun.illuminance_lux, sky.sun.unobscured_illuminance_lux, 1e-6);
  EXPECT_NEAR(lights.ephemeris.moon.elevation_deg, sky.moon.elevation_deg, 1e-9);

  // The atmosphere's sun follows it in this very update, in its own (float) fields ...
  const auto& sun = first<atmosphere::Sun>(*w);
  EXPECT_EQ(sun.azimuth_deg, float(lights.ephemeris.sun.azimuth_deg));
  EXPECT_EQ(sun.elevation_deg, float(lights.ephemeris.sun.elevation_deg));
  EXPECT_EQ(sun.illuminance_lux, float(lights.ephemeris.sun.illuminance_lux));
  EXPECT_EQ(sun.angular_radius_deg, float(lights.ephemeris.sun.angular_radius_deg));
  EXPECT_EQ(sun.visible_fraction, float(lights.ephemeris.sun.visible_fraction));
  EXPECT_NEAR(first<atmosphere::Moon>(*w).illuminated_fraction, sky.moon.illuminated_fraction, 1e-6);
  // ... and what every reader of the sun gets is exactly what the atmosphere draws.
  ASSERT_TRUE(lights.scene.sun.present);
  EXPECT_EQ(lights.scene.sun.azimuth_deg, double(sun.azimuth_deg));
  const glm::dvec3 expected = direction_from_azimuth_elevation(sun.azimuth_deg, sun.elevation_deg);
  EXPECT_EQ(scene_sun_direction(*w), std::optional<glm::vec3>(glm::vec3(expected)));
  // Within 1e-4 degrees of the SPA's worked example (float rounding is far below).
  const glm::dvec3 spa = direction_from_azimuth_elevation(194.34024, 90.0 - 50.11162);
  EXPECT_LT(glm::length(glm::dvec3(*scene_sun_direction(*w)) - spa), glm::radians(1e-4));
  EXPECT_TRUE(lights.scene.moon.present);

  // The clock, the stars it turns and the planet the atmosphere gives.
  const SceneTime& time = w->resource<SceneTime>();
  EXPECT_TRUE(time.present);
  EXPECT_EQ(time.local_time_h, kSpaExample["local_time_h"].get<double>());
  EXPECT_NEAR(time.julian_day, sky.julian_day, 1e-9);
  EXPECT_EQ(first<atmosphere::Stars>(*w).local_sidereal_time_deg, float(time.local_sidereal_time_deg));
  EXPECT_EQ(first<atmosphere::Stars>(*w).latitude_deg, float(39.742476));
  const PlanetFrame& planet = w->resource<PlanetFrame>();
  EXPECT_TRUE(planet.from_scene);
  EXPECT_EQ(planet.radius_m, 3000000.0);
  EXPECT_EQ(planet.center_m, glm::dvec3(10.0, -20.0, -3000500.0));
  EXPECT_EQ(planet.atmosphere_top_m, std::optional<double>(3080000.0));
  ASSERT_TRUE(planet.origin);
  EXPECT_EQ(planet.origin->latitude_deg, 39.742476);
  EXPECT_EQ(planet.origin->longitude_deg, -105.1786);
  const MapFrame map = scene_map_frame(*w, 5000.0);
  EXPECT_EQ(map.planet_radius_m, 3000000.0);
  EXPECT_EQ(map.planet_center_m, planet.center_m);
}

TEST(SharedState, TheClockIsFollowedInTheUpdateThatMovesIt) {
  for (bool atmosphere_first : {true, false}) {
    std::vector<const ModuleDefinition*> mods = {&modules::atmosphere_module(), &modules::timeofday_module()};
    if (!atmosphere_first) std::swap(mods[0], mods[1]);
    json clock = kSpaExample;
    clock["time_scale"] = 3600.0;
    auto w = make_world(mods, json::array({entity("clock", {{"timeofday.TimeOfDay", clock}}),
                                           entity("sun", {{"atmosphere.Sun", json::object()}})}));
    w->update({.dt_s = 1.0});  // one simulated hour
    const auto& tod = first<timeofday::TimeOfDay>(*w);
    ASSERT_NEAR(tod.local_time_h, 13.0 + 30.0 / 60 + 30.0 / 3600, 1e-9);
    EXPECT_EQ(first<atmosphere::Sun>(*w).azimuth_deg,
              float(w->resource<LightSources>().ephemeris.sun.azimuth_deg));
    EXPECT_EQ(w->resource<SceneTime>().local_time_h, tod.local_time_h) << atmosphere_first;
  }
}

TEST(SharedState, WithoutAClockTheAtmospheresOwnSunIsTheScenesSun) {
  auto w = make_world(
      {&modules::atmosphere_module(), &modules::timeofday_module()},
      json::array({entity("sun", {{"atmosphere.Sun", {{"azimuth_deg", 200}, {"elevation_deg", 10}}}}),
                   entity("light", {{"core.DirectionalLight", {{"azimuth_deg", 20}}}})}));
  w->update({});
  EXPECT_FALSE(w->resource<LightSources>().ephemeris.sun.present);
  EXPECT_FALSE(w->resource<SceneTime>().present);
  EXPECT_FALSE(w->resource<PlanetFrame>().origin);
  EXPECT_EQ(scene_sun_direction(*w),
            std::optional<glm::vec3>(glm::vec3(direction_from_azimuth_elevation(200, 10))));
  EXPECT_FALSE(w->resource<LightSources>().scene.moon.present);
  EXPECT_FALSE(w->resource<PlanetFrame>().from_scene) << "a sun without an Atmosphere gives no planet";
  EXPECT_EQ(first<DirectionalLight>(*w).azimuth_deg, 20.0f) << "no ephemeris for the default light to follow";
}

TEST(SharedState, WithoutAnAtmosphereTheDefaultLightFollowsTheEphemeris) {
  auto w = make_world({&modules::timeofday_module()},
                      json::array({entity("clock", {{"timeofday.TimeOfDay", kSpaExample}}),
                                   entity("light", {{"core.DirectionalLight", json::object()}})}));
  w->update({});
  const timeofday::SkyState sky = spa_example_sky();
  const auto& light = first<DirectionalLight>(*w);
  EXPECT_NEAR(light.azimuth_deg, sky.sun.azimuth_deg, 1e-4);
  EXPECT_NEAR(light.illuminance_lux, sky.sun.illuminance_lux * std::sin(glm::radians(sky.sun.elevation_deg)),
              0.1);
  EXPECT_GT(light.illuminance_lux, 80000.0f);
  EXPECT_FALSE(w->resource<LightSources>().scene.sun.present);
  EXPECT_EQ(scene_sun_direction(*w), std::optional<glm::vec3>(glm::vec3(direction_from_azimuth_elevation(
                                         light.azimuth_deg, light.elevation_deg))));
  // Earth's 6360 km below the origin, the default of the runtime and of the painted maps.
  EXPECT_FALSE(w->resource<PlanetFrame>().from_scene);
  EXPECT_EQ(scene_map_frame(*w, 1.0).planet_radius_m, 6360000.0);
  EXPECT_EQ(scene_map_frame(*w, 1.0).planet_center_m, glm::dvec3(0.0, 0.0, -6360000.0));
}

TEST(SharedState, AWriterThatWentAwayLeavesNothingBehind) {
  auto w = make_world({&modules::atmosphere_module(), &modules::timeofday_module()},
                      json::array({entity("clock", {{"timeofday.TimeOfDay", kSpaExample}}),
                                   entity("sun", {{"atmosphere.Sun", json::object()}})}));
  w->update({});
  const float followed = first<atmosphere::Sun>(*w).azimuth_deg;
  w->registry().destroy(w->registry().first<timeofday::TimeOfDay>());
  first<atmosphere::Sun>(*w).azimuth_deg = 10.0f;  // the user's sun, no longer overwritten
  w->update({});
  EXPECT_NE(followed, 10.0f);
  EXPECT_EQ(first<atmosphere::Sun>(*w).azimuth_deg, 10.0f);
  EXPECT_FALSE(w->resource<LightSources>().ephemeris.sun.present);
  EXPECT_FALSE(w->resource<SceneTime>().present);
  EXPECT_EQ(w->resource<LightSources>().scene.sun.azimuth_deg, 10.0);
}

TEST(ModuleDependencies, GodRaysLoadTheAtmosphereFirst) {
  World w;
  w.modules().add_static(modules::atmosphere_module());
  w.modules().add_static(modules::godrays_module());
  EXPECT_EQ(w.modules().manifest("godrays")->depends, std::vector<std::string>{"atmosphere"});
  w.modules().require_component("godrays.GodRays");
  EXPECT_EQ(w.modules().loaded(), (std::vector<std::string>{"core", "atmosphere", "godrays"}));
}

TEST(ModuleDependencies, GodRaysWithoutTheAtmosphereIsOneClearError) {
  World w;
  w.modules().add_static(modules::godrays_module());
  try {
    load_scene(w,
               json{{"welkin_scene", 1},
                    {"entities", json::array({entity("rays", {{"godrays.GodRays", json::object()}})})}},
               "rays.json");
    FAIL() << "loaded god rays without the atmosphere";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("rays.json"), std::string::npos) << m;
    EXPECT_NE(m.find("module 'atmosphere' is not installed (needed by 'godrays')"), std::string::npos) << m;
  }
  EXPECT_FALSE(w.modules().is_loaded("godrays"));
}

TEST(ModuleDependencies, UsesAreReadButNotLoaded) {
  World w;
  w.modules().add_static(modules::atmosphere_module());
  w.modules().add_static(modules::timeofday_module());
  EXPECT_EQ(w.modules().manifest("atmosphere")->uses, std::vector<std::string>{"timeofday"});
  EXPECT_TRUE(w.modules().manifest("atmosphere")->depends.empty());
  w.modules().require_component("atmosphere.Sun");
  EXPECT_FALSE(w.modules().is_loaded("timeofday"));
}

}  // namespace
