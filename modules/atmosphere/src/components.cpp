#include "welkin/atmosphere/components.h"

#include <cmath>
#include <sstream>

#include "welkin/core/error.h"

namespace welkin::atmosphere {

void describe(TypeBuilder<DensityLayer>& t) {
  t.tooltip(
      "density(h) = exp_term * exp(exp_scale_per_km * h) + linear_term_per_km * h + constant_term, clamped "
      "to [0, 1]");
  t.field("width_km", &DensityLayer::width_km)
      .unit("km")
      .range(0, 1e6)
      .tooltip("First layer only: the altitude where the second layer takes over");
  t.field("exp_term", &DensityLayer::exp_term).range(-1e6, 1e6);
  t.field("exp_scale_per_km", &DensityLayer::exp_scale_per_km)
      .unit("1/km")
      .range(-1e6, 1e6)
      .tooltip("Minus one over the scale height");
  t.field("linear_term_per_km", &DensityLayer::linear_term_per_km).unit("1/km").range(-1e6, 1e6);
  t.field("constant_term", &DensityLayer::constant_term).range(-1e6, 1e6);
}

DensityProfile exponential_profile(float scale_height_km) {
  return {DensityLayer{.exp_term = 1.0f, .exp_scale_per_km = -1.0f / scale_height_km}};
}

DensityProfile tent_profile(float centre_km, float half_width_km) {
  return {DensityLayer{.width_km = centre_km,
                       .linear_term_per_km = 1.0f / half_width_km,
                       .constant_term = 1.0f - centre_km / half_width_km},
          DensityLayer{.linear_term_per_km = -1.0f / half_width_km,
                       .constant_term = 1.0f + centre_km / half_width_km}};
}

void describe(TypeBuilder<Atmosphere>& t) {
  t.tooltip("Planet and air of a Hillaire 2020 sky (defaults: Earth)");
  t.validate(validate);
  // Radii span 1 km asteroids to 100 000 km gas giants; coefficients allow x1000 stress densities.
  t.field("bottom_radius_km", &Atmosphere::bottom_radius_km)
      .unit("km")
      .range(1e-3, 1e6)
      .tooltip("Ground radius");
  t.field("top_radius_km", &Atmosphere::top_radius_km)
      .unit("km")
      .range(1e-3, 1e6)
      .tooltip("Radius where the air ends; must exceed bottom_radius_km");
  t.field("rayleigh_scattering", &Atmosphere::rayleigh_scattering)
      .unit("1/km")
      .range(0, 1e4)
      .tooltip("Rayleigh scattering (= extinction) at density 1");
  t.field("rayleigh_density", &Atmosphere::rayleigh_density).max_count(2);
  t.field("mie_scattering", &Atmosphere::mie_scattering).unit("1/km").range(0, 1e4);
  t.field("mie_extinction", &Atmosphere::mie_extinction)
      .unit("1/km")
      .range(0, 1e4)
      .tooltip("At least mie_scattering; the difference is aerosol absorption");
  t.field("mie_density", &Atmosphere::mie_density).max_count(2);
  t.field("mie_phase", &Atmosphere::mie_phase)
      .values({{"cornette_shanks", int(MiePhase::cornette_shanks)},
               {"henyey_greenstein", int(MiePhase::henyey_greenstein)}});
  t.field("mie_g", &Atmosphere::mie_g).range(-0.9999, 0.9999).tooltip("Mie anisotropy; |g| < 1");
  t.field("absorption_extinction", &Atmosphere::absorption_extinction)
      .unit("1/km")
      .range(0, 1e4)
      .tooltip("Ozone: absorbs, never scatters");
  t.field("absorption_density", &Atmosphere::absorption_density).max_count(2);
  t.field("ground_albedo", &Atmosphere::ground_albedo).color().range(0, 1);
  t.field("multiple_scattering_factor", &Atmosphere::multiple_scattering_factor)
      .range(0, 10)
      .tooltip("Scales Hillaire's multiple-scattering term (1 = physical)");
  t.field("planet_center_below_origin", &Atmosphere::planet_center_below_origin)
      .tooltip("Put the planet's centre bottom_radius_km straight below the scene origin");
  t.field("planet_center_m", &Atmosphere::planet_center_m)
      .unit("m")
      .range(-1e12, 1e12)
      .tooltip("Planet centre in the scene frame, used when planet_center_below_origin is off");
  t.field("method", &Atmosphere::method)
      .values({{"lut", int(SkyMethod::lut)}, {"raymarch", int(SkyMethod::raymarch)}})
      .tooltip("lut: Hillaire 2020 sky-view LUT; raymarch: per-pixel nested raymarch (for comparison)");
  t.field("quality", &Atmosphere::quality)
      .values({{"low", 0}, {"medium", 1}, {"high", 2}, {"ultra", 3}, {"custom", 4}})
      .tooltip("LUT sizes and step counts; custom uses the fields below");
  t.field("transmittance_width", &Atmosphere::transmittance_width).range(2, 4096);
  t.field("transmittance_height", &Atmosphere::transmittance_height).range(2, 4096);
  t.field("transmittance_steps", &Atmosphere::transmittance_steps).range(1, 4096);
  t.field("multiscattering_size", &Atmosphere::multiscattering_size).range(2, 1024);
  t.field("multiscattering_steps", &Atmosphere::multiscattering_steps).range(1, 4096);
  t.field("multiscattering_iterations", &Atmosphere::multiscattering_iterations)
      .range(0, 64)
      .tooltip("Passes that solve the higher orders on the LUT itself; 0 keeps Hillaire's geometric series");
  t.field("sky_view_width", &Atmosphere::sky_view_width).range(2, 4096);
  t.field("sky_view_height", &Atmosphere::sky_view_height).range(2, 4096);
  t.field("sky_view_steps", &Atmosphere::sky_view_steps).range(1, 4096);
  t.field("aerial_perspective_width", &Atmosphere::aerial_perspective_width).range(2, 512);
  t.field("aerial_perspective_height", &Atmosphere::aerial_perspective_height).range(2, 512);
  t.field("aerial_perspective_slices", &Atmosphere::aerial_perspective_slices).range(2, 512);
  t.field("aerial_perspective_steps_per_slice", &Atmosphere::aerial_perspective_steps_per_slice).range(1, 64);
  t.field("aerial_perspective_distance_km", &Atmosphere::aerial_perspective_distance_km)
      .unit("km")
      .range(1e-3, 1e5)
      .tooltip("Depth of the froxel volume; slices are spaced quadratically");
  t.field("raymarch_steps", &Atmosphere::raymarch_steps)
      .range(1, 4096)
      .tooltip("Per-pixel march length: the sky seen from space, and every pixel with method raymarch");
  t.field("raymarch_light_steps", &Atmosphere::raymarch_light_steps)
      .range(1, 4096)
      .tooltip("Method raymarch: steps of each per-sample march towards the sun or moon");
}

void describe(TypeBuilder<Sun>& t) {
  t.tooltip("The sun: light of the atmosphere and a limb-darkened disc");
  t.field("azimuth_deg", &Sun::azimuth_deg).unit("deg").range(-360, 360).tooltip("Clockwise from north");
  t.field("elevation_deg", &Sun::elevation_deg).unit("deg").range(-90, 90);
  t.field("illuminance_lux", &Sun::illuminance_lux)
      .unit("lx")
      .range(0, 1e6)
      .tooltip("Outside the atmosphere, on a plane facing the sun");
  t.field("angular_radius_deg", &Sun::angular_radius_deg).unit("deg").range(1e-3, 45);
  t.field("color", &Sun::color).color().range(0, 10);
  t.field("visible_fraction", &Sun::visible_fraction).range(0, 1).tooltip("Eclipses and other occluders");
  t.field("disc", &Sun::disc);
  t.field("limb_darkening", &Sun::limb_darkening);
}

void describe(TypeBuilder<Moon>& t) {
  t.tooltip("The moon: a phase-lit disc and the night sky's light");
  t.field("azimuth_deg", &Moon::azimuth_deg).unit("deg").range(-360, 360).tooltip("Clockwise from north");
  t.field("elevation_deg", &Moon::elevation_deg).unit("deg").range(-90, 90);
  t.field("illuminance_lux", &Moon::illuminance_lux)
      .unit("lx")
      .range(0, 100)
      .tooltip("Outside the atmosphere, for the current phase (about 0.25 lx at full moon)");
  t.field("angular_radius_deg", &Moon::angular_radius_deg).unit("deg").range(1e-3, 45);
  t.field("illuminated_fraction", &Moon::illuminated_fraction).range(0, 1);
  t.field("color", &Moon::color).color().range(0, 10);
  t.field("disc", &Moon::disc);
  t.field("lights_sky", &Moon::lights_sky).tooltip("Moonlight scatters in the atmosphere");
}

ResolvedQuality resolve_quality(const Atmosphere& a) {
  switch (a.quality) {
    case Quality::low:
      return {128, 32, 20, 24, 15, 1, 96, 54, 16, 16, 16, 16, 1, 16, 4};
    case Quality::medium:
      return {256, 64, 30, 32, 15, 2, 144, 81, 20, 32, 32, 32, 1, 20, 6};
    // Method raymarch at the default quality is the seeds' 24 x 8 steps.
    case Quality::high:
      return {256, 64, 40, 48, 30, 2, 192, 108, 30, 32, 32, 32, 2, 24, 8};
    case Quality::ultra:
      return {512, 128, 80, 64, 40, 3, 384, 216, 60, 64, 64, 64, 2, 48, 16};
    case Quality::custom:
      break;
  }
  return {a.transmittance_width,
          a.transmittance_height,
          a.transmittance_steps,
          a.multiscattering_size,
          a.multiscattering_steps,
          a.multiscattering_iterations,
          a.sky_view_width,
          a.sky_view_height,
          a.sky_view_steps,
          a.aerial_perspective_width,
          a.aerial_perspective_height,
          a.aerial_perspective_slices,
          a.aerial_perspective_steps_per_slice,
          a.raymarch_steps,
          a.raymarch_light_steps};
}

glm::dvec2 mie_legendre_moments(MiePhase phase, double g) {
  if (phase == MiePhase::henyey_greenstein) return {g, g * g};
  const double k = 3.0 / (2.0 * (2.0 + g * g)), g2 = g * g;
  // c^2 P1 = 2/5 P3 + 3/5 P1;  c^2 P2 = 12/35 P4 + 11/21 P2 + 2/15 P0.
  return {k * (g + 0.4 * g2 * g + 0.6 * g), k * (g2 + 12.0 / 35.0 * g2 * g2 + 11.0 / 21.0 * g2 + 2.0 / 15.0)};
}

glm::dvec3 planet_center_m(const Atmosphere& a) {
  return a.planet_center_below_origin ? glm::dvec3(0.0, 0.0, -a.bottom_radius_km * 1000.0)
                                      : a.planet_center_m;
}

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

[[noreturn]] void fail(const std::string& path, const std::string& expected, const std::string& found) {
  throw Error(ErrorInfo{.path = path, .expected = expected, .found = found});
}

}  // namespace

void validate(const Atmosphere& a) {
  const std::string base;  // paths are relative to the component; callers prefix where it lives
  // The GPU works in float: a shell thinner than ~1e-5 of the radius cannot be resolved.
  if (!(a.top_radius_km > a.bottom_radius_km * (1.0 + 1e-5)))
    fail(base + "/top_radius_km",
         "greater than bottom_radius_km (" + number(a.bottom_radius_km) + ") by at least 1e-5 of it",
         number(a.top_radius_km));
  for (int c = 0; c < 3; ++c)
    if (a.mie_extinction[c] < a.mie_scattering[c])
      fail(base + "/mie_extinction/" + std::to_string(c),
           "at least mie_scattering (" + number(a.mie_scattering[c]) + "): absorption cannot be negative",
           number(a.mie_extinction[c]));
}


}  // namespace welkin::atmosphere
