// The timeofday module in a world (static build, same registration as the plugin).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/scene_file.h"
#include "welkin/timeofday/components.h"

namespace welkin::modules {
const ModuleDefinition& timeofday_module();
}

namespace {

using namespace welkin;
using nlohmann::json;
using timeofday::TimeOfDay;

std::unique_ptr<World> make_world(const json& tod_fields) {
  auto w = std::make_unique<World>();
  w->modules().add_static(modules::timeofday_module());
  json doc{{"welkin_scene", 1},
           {"entities", json::array({json{{"name", "clock"}, {"components", {{"timeofday.TimeOfDay", tod_fields}}}},
                                     json{{"name", "sun"}, {"components", {{"core.DirectionalLight", json::object()}}}}})}};
  load_scene(*w, doc, "test.json");
  return w;
}

TEST(TimeOfDayModule, DrivesTheLightToTheSpaWorkedExample) {
  // Reda & Andreas 2004, table A5.1: topocentric zenith 50.11162, azimuth 194.34024.
  auto w = make_world({{"year", 2003}, {"month", 10}, {"day", 17}, {"local_time_h", 12.0 + 30.0 / 60 + 30.0 / 3600},
                       {"utc_offset_h", -7}, {"latitude_deg", 39.742476}, {"longitude_deg", -105.1786},
                       {"elevation_m", 1830.14}, {"pressure_mbar", 820}, {"temperature_c", 11},
                       {"delta_t_mode", "manual"}, {"delta_t_s", 67}});
  w->update({});
  auto* light = w->registry().get<DirectionalLight>(w->registry().first<DirectionalLight>());
  EXPECT_NEAR(light->azimuth_deg, 194.34024, 1e-3);
  EXPECT_NEAR(90.0 - light->elevation_deg, 50.11162, 1e-3);
  EXPECT_GT(light->illuminance_lux, 80000.0f);
}

TEST(TimeOfDayModule, ClockAdvancesAcrossMidnightAndLeapDays) {
  auto w = make_world({{"year", 2024}, {"month", 2}, {"day", 28}, {"local_time_h", 23.5}, {"time_scale", 3600}});
  w->update({.dt_s = 1.0});  // one simulated hour
  auto* tod = w->registry().get<TimeOfDay>(w->registry().first<TimeOfDay>());
  EXPECT_EQ(tod->day, 29);
  EXPECT_EQ(tod->month, 2);
  EXPECT_NEAR(tod->local_time_h, 0.5, 1e-9);
  tod->year = 2023;
  tod->day = 28;
  tod->local_time_h = 23.5;
  w->update({.dt_s = 1.0});
  EXPECT_EQ(tod->month, 3) << "2023 is not a leap year";
  EXPECT_EQ(tod->day, 1);
}

TEST(TimeOfDayModule, PolarNightKeepsTheLightOff) {
  auto w = make_world({{"year", 2025}, {"month", 12}, {"day", 21}, {"local_time_h", 12}, {"latitude_deg", 89.9}});
  w->update({});
  auto* light = w->registry().get<DirectionalLight>(w->registry().first<DirectionalLight>());
  EXPECT_LT(light->elevation_deg, -20.0f);
  EXPECT_EQ(light->illuminance_lux, 0.0f);
}

TEST(TimeOfDayModule, ImpossibleDateIsAnErrorWhereItIsWritten) {
  try {
    make_world({{"month", 2}, {"day", 30}});
    FAIL();
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("test.json"), std::string::npos) << m;
    EXPECT_NE(m.find("/entities/0/components/timeofday.TimeOfDay"), std::string::npos) << m;
    EXPECT_NE(m.find("day"), std::string::npos) << m;
  }
}

TEST(TimeOfDayModule, NotLoadedUnlessTheSceneUsesIt) {
  World w;
  w.modules().add_static(modules::timeofday_module());
  load_scene(w, json{{"welkin_scene", 1}, {"entities", json::array({json{{"components", {{"core.Camera", json::object()}}}}})}}, "x");
  EXPECT_FALSE(w.modules().is_loaded("timeofday"));
}

}  // namespace
