// The light a cloud reference scene receives: a directional sun and a uniform sky.
#pragma once

#include <glm/vec3.hpp>

namespace welkin::clouds::reference {

struct Lighting {
  glm::dvec3 sun_direction{0.0, 0.0, 1.0};  // Unit, pointing towards the sun.
  double sun_irradiance = 1.0;              // On a plane facing the sun (arbitrary units).
  // Radiance arriving from every direction outside the medium, above and below alike; it is also
  // the background a camera ray sees behind the medium.
  double sky_radiance = 0.0;
};

}  // namespace welkin::clouds::reference
