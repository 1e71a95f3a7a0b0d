#pragma once
#include <glm/glm.hpp>

#include "welkin/core/system.h"
#include "welkin/terrain/components.h"

namespace welkin {
class World;
}

namespace welkin::terrain {
// Where a terrain's model origin sits in the scene frame (metres; geodetic anchors need a
// timeofday.TimeOfDay for the scene origin's latitude and longitude). Throws Error otherwise.
glm::dvec3 anchor_position(World& world, const Terrain& terrain);
void terrain_system(SystemContext& sc);
// Declares the sun's cascaded shadows as a term of the world's light environment (every material).
void add_light_term(World& world);
}  // namespace welkin::terrain
