// Entry point of the atmosphere module: its components, its part of the shared state and its render
// systems.
#include "shared_state.h"
#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/gpu.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"
#include "welkin/scene/shared_state.h"

namespace welkin::modules {

void register_atmosphere(ModuleContext& ctx) {
  using namespace welkin::atmosphere;
  ctx.component<Atmosphere>();
  ctx.component<Sun>();
  ctx.component<Moon>();
  ctx.component<Stars>();
  add_light_term(ctx.world());
  // After the time of day has written the ephemeris and the clock, before anything renders.
  ctx.system({.name = "atmosphere.shared_state",
              .stage = Stage::complete_shared_state,
              .optional_reads = {type_id<Atmosphere>(), type_id<Sun>(), type_id<Moon>(), type_id<Stars>()},
              .run = shared_state_system});
  // LUTs and the sky first, so every material drawn this frame reads this frame's tables and covers
  // the sky; the aerial perspective over the depth buffer once the geometry is in.
  ctx.system({.name = "atmosphere.luts",
              .stage = Stage::tables,
              .reads = {type_id<Atmosphere>()},
              .optional_reads = {type_id<Sun>(), type_id<Moon>(), type_id<Stars>()},
              .run = lut_system});
  // The sky behind the geometry, after what the light environment reads is made (the light maps).
  ctx.system({.name = "atmosphere.sky_background",
              .stage = Stage::background,
              .reads = {type_id<Atmosphere>()},
              .optional_reads = {type_id<Stars>()},
              .run = background_system});
  ctx.system({.name = "atmosphere.sky",
              .stage = Stage::aerial_perspective,
              .reads = {type_id<Atmosphere>()},
              .run = sky_system});
}

}  // namespace welkin::modules
