// The light a cloud reference scene receives: a directional sun, a uniform sky and a uniform ground.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace welkin::clouds::reference {

struct Lighting {
  glm::dvec3 sun_direction{0.0, 0.0, 1.0};  // Unit, pointing towards the sun.
  double sun_irradiance = 1.0;              // On a plane facing the sun (arbitrary units).
  // Radiance arriving from outside the medium along a direction that misses the ground (the sky)
  // and along one that meets it (the ground, a uniform emitter: no bounce is traced). Both are also
  // what a camera ray sees behind the medium.
  double sky_radiance = 0.0;
  double ground_radiance = 0.0;
  // The ground: the sphere of planet_radius_m around planet_center_m; radius 0 is a flat ground
  // below the horizontal plane (a direction with z < 0 meets it).
  glm::dvec3 planet_center_m{0.0};
  double planet_radius_m = 0.0;

  // Radiance arriving at x from outside the medium along -direction (a path leaving x along it).
  double environment(const glm::dvec3& x, const glm::dvec3& direction) const {
    if (planet_radius_m <= 0.0) return direction.z < 0.0 ? ground_radiance : sky_radiance;
    // The ray x + t d meets the sphere for some t > 0: its closest approach lies ahead of x and
    // inside the sphere (x itself outside or on it).
    const glm::dvec3 to_center = planet_center_m - x;
    const double along = glm::dot(to_center, direction);
    const double miss2 = glm::dot(to_center, to_center) - along * along;
    return along > 0.0 && miss2 < planet_radius_m * planet_radius_m ? ground_radiance : sky_radiance;
  }
};

}  // namespace welkin::clouds::reference
