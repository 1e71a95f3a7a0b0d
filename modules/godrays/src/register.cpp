// Entry point of the god-rays module: its component and its render system.
#include "shafts.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/godrays/components.h"

namespace welkin::modules {

void register_godrays(ModuleContext& ctx) {
  using namespace welkin::godrays;
  ctx.component<GodRays>();
  // After the geometry and the atmosphere's aerial perspective on it (order 100), before the clouds
  // (150): the air in front of the clouds is what the shafts darken, and their composite scales it.
  ctx.system({.name = "godrays.shafts", .phase = Phase::render, .order = 140,
              .reads = {type_id<GodRays>()}, .run = shafts_system});
}

}  // namespace welkin::modules
