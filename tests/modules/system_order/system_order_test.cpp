// The order every module's systems run in, resolved from named stages and `after` constraints, is the
// one the integer orders gave before them: each system's old integer below, its systems sorted by it
// (registration order between equals), must give the order the scheduler resolves now, whichever
// order the modules are loaded in.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "welkin/core/module.h"
#include "welkin/core/world.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
const ModuleDefinition& godrays_module();
const ModuleDefinition& terrain_module();
const ModuleDefinition& timeofday_module();
}  // namespace welkin::modules

namespace welkin {
namespace {

// Each system's order before the stages (the integers of the modules' register.cpp files).
const std::map<std::string, int> kIntegerOrder = {{"timeofday.sequence", 0},
                                                  {"timeofday.sun_and_moon", 0},
                                                  {"core.directional_light", 100},
                                                  {"atmosphere.shared_state", 100},
                                                  {"atmosphere.luts", -100},
                                                  {"clouds.shadows", -50},
                                                  {"atmosphere.sky_background", -10},
                                                  {"core.backdrop", 0},
                                                  {"core.debug_shapes", 0},
                                                  {"terrain.draw", 0},
                                                  {"atmosphere.sky", 100},
                                                  {"godrays.shafts", 140},
                                                  {"clouds.billboards", 144},
                                                  {"clouds.clusters", 145},
                                                  {"clouds.march", 150}};

std::unique_ptr<World> world_with_every_module(const std::vector<std::string>& load_order) {
  auto world = std::make_unique<World>();
  for (const ModuleDefinition* m :
       {&modules::atmosphere_module(), &modules::clouds_module(), &modules::godrays_module(),
        &modules::terrain_module(), &modules::timeofday_module()})
    world->modules().add_static(*m);
  for (const std::string& name : load_order) world->modules().load(name);
  return world;
}

// The order the integers gave: the phase's systems in registration order, stably sorted by them.
std::vector<std::string> integer_order(World& world, Phase phase) {
  std::vector<std::string> names;
  for (const SystemDesc& s : world.scheduler().systems())
    if (phase_of(s.stage) == phase) names.push_back(s.name);
  for (const std::string& n : names) EXPECT_TRUE(kIntegerOrder.contains(n)) << n << " has no integer order";
  std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    return kIntegerOrder.at(a) < kIntegerOrder.at(b);
  });
  return names;
}

TEST(SystemOrder, EveryModulesSystemsRunInTheOrderTheIntegersGave) {
  const std::vector<std::string> render = {
      "atmosphere.luts", "clouds.shadows",    "atmosphere.sky_background",
      "core.backdrop",   "core.debug_shapes", "terrain.draw",
      "atmosphere.sky",  "godrays.shafts",    "clouds.billboards",
      "clouds.clusters", "clouds.march"};
  const std::vector<std::string> update = {"timeofday.sequence", "timeofday.sun_and_moon",
                                           "core.directional_light", "atmosphere.shared_state"};
  for (const std::vector<std::string>& load :
       {std::vector<std::string>{"atmosphere", "clouds", "godrays", "terrain", "timeofday"},
        std::vector<std::string>{"timeofday", "terrain", "godrays", "clouds", "atmosphere"}}) {
    auto world = world_with_every_module(load);
    SCOPED_TRACE(load.front() + " loaded first");
    EXPECT_EQ(world->scheduler().ordered_names(Phase::render), render);
    EXPECT_EQ(world->scheduler().ordered_names(Phase::render), integer_order(*world, Phase::render));
    EXPECT_EQ(world->scheduler().ordered_names(Phase::update), update);
    EXPECT_EQ(world->scheduler().ordered_names(Phase::update), integer_order(*world, Phase::update));
    EXPECT_TRUE(world->scheduler().ordered_names(Phase::pre_render).empty());
  }
}

}  // namespace
}  // namespace welkin
