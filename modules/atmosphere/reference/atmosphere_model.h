// Atmosphere description shared by every CPU reference: Bruneton 2017 density layers and the
// Hillaire 2020 Earth constants. Lengths in km, coefficients in 1/km, RGB as glm::dvec3.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace welkin::atmosphere::reference {

inline constexpr double kPi = 3.14159265358979323846;

// One layer of a density profile, in Bruneton's form:
// density(h) = exp_term * exp(exp_scale_per_km * h) + linear_term_per_km * h + constant_term.
struct DensityLayer {
  double width_km = 0.0;  // Only meaningful for layer 0: the altitude where layer 1 takes over.
  double exp_term = 0.0;
  double exp_scale_per_km = 0.0;
  double linear_term_per_km = 0.0;
  double constant_term = 0.0;
};

// Two-layer profile with Bruneton's semantics: layer 0 below layers[0].width_km, layer 1 at and
// above it, the result clamped to [0, 1]. The clamp is what lets a tracker use a constant majorant.
struct DensityProfile {
  DensityLayer layers[2];

  // Relative density at an altitude above the ground, in [0, 1].
  double density(double altitude_km) const;
  // Altitudes where the profile has a kink (layer switch, clamp onset) that quadrature should
  // split at. Mixed exponential + linear layers contribute no clamp altitudes (adaptivity copes).
  std::vector<double> kink_altitudes_km() const;
};

// Which anisotropic phase function Mie scattering uses (both parametrised by mie_g).
enum class MiePhase { cornette_shanks, henyey_greenstein };

// Scattering and absorption coefficients at one point, already multiplied by the densities.
struct LocalCoefficients {
  glm::dvec3 rayleigh_scattering{0.0};
  glm::dvec3 mie_scattering{0.0};
  glm::dvec3 extinction{0.0};  // Rayleigh scattering + Mie extinction + absorption.
};

// A spherical planet with a spherical-shell atmosphere. Density is zero outside the shell.
// Default constructed it is an empty (vacuum) Earth-sized shell; earth() fills it in.
struct AtmosphereModel {
  double bottom_radius_km = 6360.0;
  double top_radius_km = 6460.0;
  glm::dvec3 rayleigh_scattering{0.0};  // Rayleigh scattering = extinction (no absorption).
  DensityProfile rayleigh_density;
  glm::dvec3 mie_scattering{0.0};
  glm::dvec3 mie_extinction{0.0};  // >= mie_scattering; the difference is Mie absorption.
  DensityProfile mie_density;
  MiePhase mie_phase = MiePhase::cornette_shanks;
  double mie_g = 0.8;
  glm::dvec3 absorption_extinction{0.0};  // Ozone: absorbs, never scatters.
  DensityProfile absorption_density;
  glm::dvec3 ground_albedo{0.3};  // Lambertian.

  // Hillaire 2020 / Bruneton 2017 Earth: Rayleigh H = 8 km, Mie H = 1.2 km and g = 0.8,
  // ozone tent centred at 25 km with 15 km half width, radii 6360 / 6460 km, albedo 0.3.
  static AtmosphereModel earth();

  // Every problem with the description, one readable line each; empty when usable.
  std::vector<std::string> validate() const;

  // Same optical depths and radiances on a planet whose lengths are all multiplied by
  // length_factor (coefficients divided by it): a scale-invariance check for the integrators.
  AtmosphereModel scaled(double length_factor) const;
  // All coefficients multiplied by factor (density x0, x1000 stress cases).
  AtmosphereModel with_density_scale(double factor) const;

  double thickness_km() const { return top_radius_km - bottom_radius_km; }
  // Coefficients at an altitude above the ground; zero outside [0, thickness].
  LocalCoefficients coefficients(double altitude_km) const;
  // Extinction only; the hot path of transmittance quadrature.
  glm::dvec3 extinction(double altitude_km) const;
  // Upper bound of the extinction anywhere (densities are clamped to 1): a valid majorant.
  double max_extinction() const;
  // Mie phase function of this model at the cosine of the scattering angle.
  double mie_phase_value(double cos_theta) const;
  // Altitudes of every kink of every profile, sorted, inside (0, thickness).
  std::vector<double> kink_altitudes_km() const;
};

// Phase functions of the cosine between the propagation directions of the incident and the
// scattered light (equivalently dot(view, sun)). Each integrates to 1 over the sphere (1/sr).
double rayleigh_phase(double cos_theta);
// Cornette-Shanks 1992: Henyey-Greenstein with a Rayleigh-like (1 + mu^2) factor, renormalised.
double cornette_shanks_phase(double g, double cos_theta);
// Henyey-Greenstein 1941: mean cosine g. Both stay exact in their peaks up to |g| = 0.999.
double henyey_greenstein_phase(double g, double cos_theta);

}  // namespace welkin::atmosphere::reference
