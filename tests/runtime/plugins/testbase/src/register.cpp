#include "welkin/core/module.h"
#include "welkin/core/world.h"

namespace testbase {
struct Counter {
  static constexpr std::string_view kTypeName = "testbase.Counter";
  int ticks = 0;
  float rate = 1.0f;
};
void describe(welkin::TypeBuilder<Counter>& t) {
  t.field("ticks", &Counter::ticks).range(0, 1e9);
  t.field("rate", &Counter::rate).unit("1/s").range(0, 100);
}
}  // namespace testbase

namespace welkin::modules {
void register_testbase(ModuleContext& ctx) {
  ctx.component<testbase::Counter>();
  ctx.system({.name = "testbase.tick", .stage = Stage::simulate, .writes = {type_id<testbase::Counter>()},
              .run = [](SystemContext& sc) {
                sc.world.registry().each<testbase::Counter>([](Entity, testbase::Counter& c) { ++c.ticks; });
              }});
}
}  // namespace welkin::modules
