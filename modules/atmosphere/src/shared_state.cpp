#include "shared_state.h"

#include "welkin/atmosphere/components.h"
#include "welkin/atmosphere/stars.h"
#include "welkin/core/world.h"
#include "welkin/scene/shared_state.h"

namespace welkin::atmosphere {

namespace {

template <class T>
T* first(Registry& reg) {
  const Entity e = reg.first<T>();
  return e.is_null() ? nullptr : reg.get<T>(e);
}

// The components store floats: the shared state carries exactly what is drawn.
LightSource drawn(const Sun& sun) {
  return {.present = true,
          .azimuth_deg = sun.azimuth_deg,
          .elevation_deg = sun.elevation_deg,
          .illuminance_lux = sun.illuminance_lux,
          .angular_radius_deg = sun.angular_radius_deg,
          .visible_fraction = sun.visible_fraction};
}

LightSource drawn(const Moon& moon) {
  return {.present = true,
          .azimuth_deg = moon.azimuth_deg,
          .elevation_deg = moon.elevation_deg,
          .illuminance_lux = moon.illuminance_lux,
          .angular_radius_deg = moon.angular_radius_deg,
          .illuminated_fraction = moon.illuminated_fraction};
}

}  // namespace

void shared_state_system(SystemContext& sc) {
  World& world = sc.world;
  Registry& reg = world.registry();
  LightSources& lights = world.resource<LightSources>();
  const SceneTime& time = world.resource<SceneTime>();
  PlanetFrame& planet = world.resource<PlanetFrame>();
  Sun* sun = first<Sun>(reg);
  Moon* moon = first<Moon>(reg);
  Stars* stars = first<Stars>(reg);
  if (const LightSource& e = lights.ephemeris.sun; sun && e.present) {
    sun->azimuth_deg = float(e.azimuth_deg);
    sun->elevation_deg = float(e.elevation_deg);
    sun->illuminance_lux = float(e.illuminance_lux);
    sun->angular_radius_deg = float(e.angular_radius_deg);
    sun->visible_fraction = float(e.visible_fraction);
  }
  if (const LightSource& e = lights.ephemeris.moon; moon && e.present) {
    moon->azimuth_deg = float(e.azimuth_deg);
    moon->elevation_deg = float(e.elevation_deg);
    moon->illuminance_lux = float(e.illuminance_lux);
    moon->angular_radius_deg = float(e.angular_radius_deg);
    moon->illuminated_fraction = float(e.illuminated_fraction);
  }
  if (stars && time.present) stars->local_sidereal_time_deg = float(time.local_sidereal_time_deg);
  if (stars && planet.origin) stars->latitude_deg = float(planet.origin->latitude_deg);

  if (sun) lights.scene.sun = drawn(*sun);
  if (moon) lights.scene.moon = drawn(*moon);
  if (const Atmosphere* atm = first<Atmosphere>(reg)) {
    planet.from_scene = true;
    planet.radius_m = atm->bottom_radius_km * 1000.0;
    planet.center_m = planet_center_m(*atm);
    planet.atmosphere_top_m = atm->top_radius_km * 1000.0;
  }
}

}  // namespace welkin::atmosphere
