// The scheduler's order: named stages in their order, `after` within a stage, registration order where
// nothing constrains; a name no system of the stage has, and a cycle, are errors that name them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "welkin/core/error.h"
#include "welkin/core/system.h"
#include "welkin/core/world.h"

namespace welkin {
namespace {

SystemDesc system(std::string name, Stage stage, std::vector<std::string> after = {}) {
  return {.name = std::move(name), .stage = stage, .after = std::move(after), .run = [](SystemContext&) {}};
}

// The message of the Error `order` throws ("" when it throws none).
std::string order_error(Scheduler& s, Phase phase) {
  try {
    s.ordered_names(phase);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scheduler, StagesRunInTheirOrderWhateverTheRegistrationOrder) {
  Scheduler s;
  s.add(system("clouds", Stage::clouds));
  s.add(system("geometry", Stage::geometry));
  s.add(system("tables", Stage::tables));
  s.add(system("shared", Stage::complete_shared_state));
  s.add(system("clock", Stage::simulate));
  s.add(system("shafts", Stage::light_shafts));
  s.add(system("sky", Stage::aerial_perspective));
  s.add(system("background", Stage::background));
  s.add(system("shadows", Stage::light_maps));
  EXPECT_EQ(
      s.ordered_names(Phase::render),
      (std::vector<std::string>{"tables", "shadows", "background", "geometry", "sky", "shafts", "clouds"}));
  EXPECT_EQ(s.ordered_names(Phase::update), (std::vector<std::string>{"clock", "shared"}));
}

TEST(Scheduler, AfterOrdersWithinAStageAndRegistrationOrderHoldsElsewhere) {
  Scheduler s;
  s.add(system("c", Stage::clouds, {"b"}));
  s.add(system("x", Stage::clouds));
  s.add(system("b", Stage::clouds, {"a"}));
  s.add(system("a", Stage::clouds));
  s.add(system("y", Stage::clouds));
  // a is the first with nothing to wait for after x; b and c follow as soon as they may.
  EXPECT_EQ(s.ordered_names(Phase::render), (std::vector<std::string>{"x", "a", "b", "c", "y"}));
  s.add(system("z", Stage::clouds, {"y", "x"}));
  EXPECT_EQ(s.ordered_names(Phase::render), (std::vector<std::string>{"x", "a", "b", "c", "y", "z"}));
}

TEST(Scheduler, RunsTheSystemsOfAPhaseInTheResolvedOrder) {
  World world;
  std::vector<std::string> ran;
  auto record = [&ran](std::string name) { return [&ran, name](SystemContext&) { ran.push_back(name); }; };
  world.scheduler().add(
      {.name = "test.second", .stage = Stage::simulate, .after = {"test.first"}, .run = record("second")});
  world.scheduler().add({.name = "test.first", .stage = Stage::simulate, .run = record("first")});
  world.scheduler().add(
      {.name = "test.shared", .stage = Stage::complete_shared_state, .run = record("shared")});
  world.update({});
  const std::vector<std::string> expected = {"first", "second", "shared"};
  EXPECT_EQ(std::vector<std::string>(ran.end() - 3, ran.end()), expected);
}

// `before` is how a module orders itself ahead of one it depends on (registered earlier, and which
// cannot name it): the weather's report before the time of day's sun.
TEST(Scheduler, BeforePutsASystemAheadOfOneRegisteredEarlier) {
  Scheduler s;
  s.add(system("timeofday.sequence", Stage::simulate));
  s.add(system("timeofday.sun_and_moon", Stage::simulate, {"timeofday.sequence"}));
  SystemDesc report = system("weather.apply_report", Stage::simulate);
  report.before = {"timeofday.sun_and_moon"};
  s.add(report);
  const std::vector<std::string> expected = {"timeofday.sequence", "weather.apply_report", "timeofday.sun_and_moon"};
  EXPECT_EQ(s.ordered_names(Phase::update), expected);
  Scheduler t;
  SystemDesc lost = system("weather.apply_report", Stage::simulate);
  lost.before = {"timeofday.sun"};
  t.add(lost);
  const std::string e = order_error(t, Phase::update);
  EXPECT_NE(e.find("weather.apply_report/before"), std::string::npos) << e;
  EXPECT_NE(e.find("'timeofday.sun', which no system is named"), std::string::npos) << e;
}

TEST(Scheduler, AnUnknownNameIsAnErrorNamingBothSystems) {
  Scheduler s;
  s.add(system("clouds.billboards", Stage::clouds));
  s.add(system("clouds.clusters", Stage::clouds, {"clouds.bilboards"}));
  const std::string e = order_error(s, Phase::render);
  EXPECT_NE(e.find("clouds.clusters"), std::string::npos) << e;
  EXPECT_NE(e.find("'clouds.bilboards', which no system is named"), std::string::npos) << e;
}

TEST(Scheduler, AfterASystemOfAnotherStageIsAnError) {
  Scheduler s;
  s.add(system("atmosphere.sky", Stage::aerial_perspective));
  s.add(system("godrays.shafts", Stage::light_shafts, {"atmosphere.sky"}));
  const std::string e = order_error(s, Phase::render);
  EXPECT_NE(e.find("godrays.shafts"), std::string::npos) << e;
  EXPECT_NE(e.find("'atmosphere.sky', of stage aerial_perspective"), std::string::npos) << e;
}

TEST(Scheduler, ACycleIsAnErrorNamingTheSystemsInIt) {
  Scheduler s;
  s.add(system("free", Stage::geometry));
  s.add(system("a", Stage::geometry, {"c"}));
  s.add(system("b", Stage::geometry, {"a"}));
  s.add(system("c", Stage::geometry, {"b"}));
  const std::string e = order_error(s, Phase::render);
  EXPECT_NE(e.find("cycle of `after`/`before` among a, b, c"), std::string::npos) << e;
  EXPECT_EQ(e.find("free"), std::string::npos) << e;
  // A system after itself is the smallest cycle.
  Scheduler t;
  t.add(system("self", Stage::clouds, {"self"}));
  EXPECT_NE(order_error(t, Phase::render).find("among self"), std::string::npos);
}

}  // namespace
}  // namespace welkin
