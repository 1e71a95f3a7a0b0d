// Entry point of the god-rays module: its component and its render system.
#include "shafts.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/godrays/components.h"

namespace welkin::modules {

void register_godrays(ModuleContext& ctx) {
  using namespace welkin::godrays;
  ctx.component<GodRays>();
  ctx.component<Haze>();
  // After the geometry and the atmosphere's aerial perspective on it, before the clouds (the stages'
  // order): the air in front of the clouds is what the shafts darken, and their composite scales it.
  // The module is loaded only for a scene with either component; the system draws what it finds.
  ctx.system({.name = "godrays.shafts", .stage = Stage::light_shafts,
              .optional_reads = {type_id<GodRays>(), type_id<Haze>()}, .run = shafts_system});
}

}  // namespace welkin::modules
