// The weather module in a world (static build, the same registration as the plugin): a report sets
// the scene's clock, place, cloud layers and haze once, through the other modules' components, and a
// bad one is one error naming the scene file, the component and the group.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "welkin/atmosphere/components.h"
#include "welkin/clouds/components.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/scene_file.h"
#include "welkin/timeofday/components.h"
#include "welkin/weather/components.h"
#include "welkin/weather/station_table.h"

namespace welkin::modules {
const ModuleDefinition& timeofday_module();
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
const ModuleDefinition& weather_module();
}  // namespace welkin::modules

namespace {

using namespace welkin;
using nlohmann::json;

std::unique_ptr<World> make_world(const json& components) {
  auto w = std::make_unique<World>();
  w->modules().add_static(modules::timeofday_module());
  w->modules().add_static(modules::atmosphere_module());
  w->modules().add_static(modules::clouds_module());
  w->modules().add_static(modules::weather_module());
  json doc{{"welkin_scene", 1},
           {"entities", json::array({json{{"name", "sky"}, {"components", components}}})}};
  load_scene(*w, doc, "weather.json");
  return w;
}

template <class T>
T* first(World& w) {
  return w.registry().get<T>(w.registry().first<T>());
}

const char* kSfo = "KSFO 271756Z 28012KT 10SM FEW008 SCT025 BKN250 18/12 A3001";

TEST(WeatherModule, ReportAloneGetsTheStationsPlaceClockAndLayers) {
  auto w = make_world({{"weather.Report", {{"metar", kSfo}, {"year", 2026}, {"month", 11}}}});
  w->update({});
  auto* tod = first<timeofday::TimeOfDay>(*w);
  ASSERT_TRUE(tod) << "a time of day is added for the report";
  // San Francisco International: 37.619 N, 122.375 W (FAA).
  EXPECT_NEAR(tod->latitude_deg, 37.619, 0.02);
  EXPECT_NEAR(tod->longitude_deg, -122.375, 0.02);
  EXPECT_EQ(tod->year, 2026);
  EXPECT_EQ(tod->month, 11);
  EXPECT_EQ(tod->day, 27);
  EXPECT_DOUBLE_EQ(tod->local_time_h, 17.0 + 56.0 / 60.0);
  EXPECT_EQ(tod->utc_offset_h, 0.0);
  auto* vc = first<clouds::VolumetricClouds>(*w);
  ASSERT_TRUE(vc);
  ASSERT_EQ(vc->layers.size(), 3u);
  EXPECT_EQ(vc->layers[2].genus, clouds::Genus::cirrus);
  EXPECT_FLOAT_EQ(vc->coverage, 1.0f);
  EXPECT_GT(vc->wind_mps.x, 6.0f);
  EXPECT_FALSE(first<atmosphere::Atmosphere>(*w)) << "10 miles: no haze to set, no atmosphere added";
  // Applied once: the scene's own edits stand until the report changes.
  vc->layers[0].coverage = 0.9f;
  w->update({});
  EXPECT_FLOAT_EQ(vc->layers[0].coverage, 0.9f);
  first<weather::Report>(*w)->metar = "KSFO 271856Z 28012KT 10SM SKC 18/12 A3001";
  w->update({});
  EXPECT_TRUE(vc->layers.empty());
  EXPECT_DOUBLE_EQ(tod->local_time_h, 18.0 + 56.0 / 60.0);
}

TEST(WeatherModule, SceneKeepsItsOwnPlaceUnlessTheReportSaysStation) {
  json tod{{"latitude_deg", 46.5}, {"longitude_deg", 7.9}, {"month", 6}};
  auto w = make_world({{"weather.Report", {{"metar", kSfo}}}, {"timeofday.TimeOfDay", tod}});
  w->update({});
  EXPECT_EQ(first<timeofday::TimeOfDay>(*w)->latitude_deg, 46.5);
  EXPECT_EQ(first<timeofday::TimeOfDay>(*w)->month, 6);
  first<weather::Report>(*w)->place = weather::ReportPlace::station;
  w->update({});
  EXPECT_NEAR(first<timeofday::TimeOfDay>(*w)->latitude_deg, 37.617, 0.01);
}

TEST(WeatherModule, MistSetsTheHazeOfTheScenesAtmosphere) {
  auto w = make_world({{"weather.Report", {{"metar", "KORD 271751Z 19012KT 3SM BR OVC008 08/07 A2978"}}},
                       {"atmosphere.Atmosphere", json::object()},
                       {"timeofday.TimeOfDay", json::object()}});
  w->update({});
  auto* air = first<atmosphere::Atmosphere>(*w);
  double expected = std::log(20.0) / (3 * 1.609344) - 13.558e-3;
  EXPECT_NEAR(air->mie_extinction.y, expected, 1e-5);
  EXPECT_NEAR(air->mie_scattering.y / air->mie_extinction.y, 3.996 / 4.440, 1e-5)
      << "the scene's aerosol albedo kept";
  EXPECT_EQ(first<clouds::VolumetricClouds>(*w)->layers.at(0).genus, clouds::Genus::stratus)
      << "overcast below 1000 ft";
}

std::string load_error(const json& components) {
  try {
    auto w = make_world(components);
    w->update({});
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(WeatherModule, BadReportsAreOneErrorNamingFileComponentAndGroup) {
  std::string e =
      load_error({{"weather.Report", {{"metar", "KSFO 271756Z 28012KT 10SM FEW0X8 18/12 A3001"}}}});
  EXPECT_NE(e.find("weather.json"), std::string::npos) << e;
  EXPECT_NE(e.find("weather.Report/metar"), std::string::npos) << e;
  EXPECT_NE(e.find("group 5 'FEW0X8' at column 27"), std::string::npos) << e;
  e = load_error({{"weather.Report", {{"metar", "ZZZZ 271756Z 28012KT 10SM FEW008 18/12 A3001"}}}});
  EXPECT_NE(e.find("station ZZZZ"), std::string::npos) << e;
  EXPECT_NE(e.find("stations.csv"), std::string::npos) << e;
  e = load_error(
      {{"weather.Report",
        {{"metar", "KSFO 311756Z 28012KT 10SM FEW008 18/12 A3001"}, {"month", 6}, {"year", 2026}}}});
  EXPECT_NE(e.find("day 31"), std::string::npos) << e;
}

TEST(StationTable, FindsStationsAndNamesMalformedLines) {
  std::string table = std::string(WELKIN_SOURCE_DIR) + "/modules/weather/data/stations.csv";
  auto sfo = weather::find_station(table, "KSFO");
  ASSERT_TRUE(sfo);
  EXPECT_NEAR(sfo->latitude_deg, 37.619, 0.02);
  EXPECT_NEAR(sfo->longitude_deg, -122.375, 0.02);
  // London Heathrow: 51.4706 N, 0.4619 W (its AIP).
  auto lhr = weather::find_station(table, "EGLL");
  ASSERT_TRUE(lhr);
  EXPECT_NEAR(lhr->latitude_deg, 51.47, 0.02);
  EXPECT_NEAR(lhr->longitude_deg, -0.46, 0.02);
  EXPECT_FALSE(weather::find_station(table, "ZZZZ"));
  std::string bad = std::string(WELKIN_BINARY_DIR) + "/bad-stations.csv";
  write_file_atomically(bad, "# header\nKAAA,10,20,A\nKBBB,95,20,B\n");
  try {
    weather::find_station(bad, "KBBB");
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("bad-stations.csv"), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find("line 3"), std::string::npos) << err.what();
  }
}

}  // namespace
