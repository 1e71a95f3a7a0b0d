#include "welkin/scene/shared_state.h"

#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"

namespace welkin {

glm::dvec3 LightSource::direction() const {
  return direction_from_azimuth_elevation(azimuth_deg, elevation_deg);
}

void clear_shared_state(World& world) {
  // A writer whose entity went away (the editor removed the clock) leaves nothing behind.
  world.resource<PlanetFrame>() = PlanetFrame{};
  world.resource<LightSources>() = LightSources{};
  world.resource<SceneTime>() = SceneTime{};
}

}  // namespace welkin
