#pragma once
// Components of the atmosphere module (Hillaire 2020). Plain reflected structs: the reflection
// below is the single source of their JSON form, ranges, units and editor inspector. Lengths of the
// atmosphere are in km and coefficients in 1/km (as in Bruneton and Hillaire); scene positions stay
// in metres in the scene's east-north-up frame.
#include <glm/glm.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/core/reflection.h"

namespace welkin::atmosphere {

// One layer of a Bruneton density profile: density(h) = exp_term * exp(exp_scale_per_km * h)
// + linear_term_per_km * h + constant_term, clamped to [0, 1]; h is the altitude in km.
struct DensityLayer {
  static constexpr std::string_view kTypeName = "atmosphere.DensityLayer";
  float width_km = 0.0f;  // first of two layers only: the altitude where the second takes over
  float exp_term = 0.0f;
  float exp_scale_per_km = 0.0f;
  float linear_term_per_km = 0.0f;
  float constant_term = 0.0f;
};
void describe(TypeBuilder<DensityLayer>& t);

// A profile is 0, 1 or 2 layers: none is empty space, one applies at every altitude, two split at
// the first layer's width_km (Bruneton 2017's DensityProfile).
using DensityProfile = std::vector<DensityLayer>;
DensityProfile exponential_profile(float scale_height_km);
// Zero below and above, rising linearly to 1 at centre_km: the ozone layer's usual shape.
DensityProfile tent_profile(float centre_km, float half_width_km);

enum class MiePhase : int { cornette_shanks = 0, henyey_greenstein = 1 };
// Presets of LUT sizes and step counts; `custom` uses the explicit fields of Atmosphere.
enum class Quality : int { low = 0, medium = 1, high = 2, ultra = 3, custom = 4 };
// How the sky is rendered. `lut` is Hillaire 2020 (a sky-view LUT per frame, one fetch per pixel);
// `raymarch` marches every pixel with a nested march to the sun (the approach Hillaire's replaces),
// kept so that both can be measured against each other and the reference on the same frames.
enum class SkyMethod : int { lut = 0, raymarch = 1 };

// The planet and its air. Defaults are Hillaire 2020's Earth (presets/earth.json).
struct Atmosphere {
  static constexpr std::string_view kTypeName = "atmosphere.Atmosphere";
  double bottom_radius_km = 6360.0;
  double top_radius_km = 6460.0;
  glm::vec3 rayleigh_scattering{5.802e-3f, 13.558e-3f, 33.1e-3f};
  DensityProfile rayleigh_density = exponential_profile(8.0f);
  glm::vec3 mie_scattering{3.996e-3f};
  glm::vec3 mie_extinction{4.440e-3f};
  DensityProfile mie_density = exponential_profile(1.2f);
  MiePhase mie_phase = MiePhase::cornette_shanks;
  float mie_g = 0.8f;
  glm::vec3 absorption_extinction{0.650e-3f, 1.881e-3f, 0.085e-3f};
  DensityProfile absorption_density = tent_profile(25.0f, 15.0f);
  glm::vec3 ground_albedo{0.3f};
  float multiple_scattering_factor = 1.0f;
  // The planet's centre is straight below the scene origin (the origin on the ground) unless this
  // is off; then planet_center_m places it anywhere in the scene frame.
  bool planet_center_below_origin = true;
  glm::dvec3 planet_center_m{0.0, 0.0, -6360000.0};

  SkyMethod method = SkyMethod::lut;
  Quality quality = Quality::high;
  int transmittance_width = 256, transmittance_height = 64, transmittance_steps = 40;
  int multiscattering_size = 48, multiscattering_steps = 30;
  // Orders solved on the LUT after Hillaire's estimate (0: the paper's geometric series alone).
  int multiscattering_iterations = 2;
  int sky_view_width = 192, sky_view_height = 108, sky_view_steps = 30;
  int aerial_perspective_width = 32, aerial_perspective_height = 32, aerial_perspective_slices = 32;
  int aerial_perspective_steps_per_slice = 2;
  float aerial_perspective_distance_km = 128.0f;
  int raymarch_steps = 32;  // per-pixel marches: the sky seen from space, aerial perspective there
  int raymarch_light_steps = 8;  // method raymarch: steps of each march towards the sun
};
void describe(TypeBuilder<Atmosphere>& t);

// The sun as a directional light with a disc. Illuminance is outside the atmosphere, on a plane
// facing the sun; what reaches the ground is attenuated by the transmittance LUT.
struct Sun {
  static constexpr std::string_view kTypeName = "atmosphere.Sun";
  float azimuth_deg = 135.0f;  // clockwise from north
  float elevation_deg = 35.0f;
  float illuminance_lux = 120000.0f;
  float angular_radius_deg = 0.2678f;
  glm::vec3 color{1.0f};          // tint of the illuminance (linear Rec.709)
  float visible_fraction = 1.0f;  // eclipses and other occluders supplied by other modules
  bool disc = true;
  bool limb_darkening = true;
};
void describe(TypeBuilder<Sun>& t);

// The moon: a phase-lit disc and, optionally, a second light for the night sky. The time-of-day
// module supplies its direction, phase-dependent illuminance and illuminated fraction.
struct Moon {
  static constexpr std::string_view kTypeName = "atmosphere.Moon";
  float azimuth_deg = 300.0f;
  float elevation_deg = 25.0f;
  float illuminance_lux = 0.25f;  // outside the atmosphere, for the current phase
  float angular_radius_deg = 0.2575f;
  float illuminated_fraction = 1.0f;
  glm::vec3 color{1.0f};
  bool disc = true;
  bool lights_sky = true;  // moonlight scatters in the air (a sun-less night sky is not black)
};
void describe(TypeBuilder<Moon>& t);

// LUT sizes and step counts after applying `quality` (custom keeps the explicit fields).
struct ResolvedQuality {
  int transmittance_width, transmittance_height, transmittance_steps;
  int multiscattering_size, multiscattering_steps, multiscattering_iterations;
  int sky_view_width, sky_view_height, sky_view_steps;
  int aerial_perspective_width, aerial_perspective_height, aerial_perspective_slices;
  int aerial_perspective_steps_per_slice;
  int raymarch_steps;
  int raymarch_light_steps;
};
ResolvedQuality resolve_quality(const Atmosphere& a);

// Legendre moments lambda_1 and lambda_2 of the Mie phase function (2 pi times the integral of
// p(c) P_l(c) over c): Henyey-Greenstein's are g^l; Cornette-Shanks, HG times 3 (1 + c^2) /
// (2 (2 + g^2)), follows from HG's through c^2 P_l = sums of P_(l-2), P_l, P_(l+2).
glm::dvec2 mie_legendre_moments(MiePhase phase, double g);

// Planet centre in the scene frame (metres), honouring planet_center_below_origin.
glm::dvec3 planet_center_m(const Atmosphere& a);

// Cross-field checks the per-field ranges cannot express (top above bottom, Mie extinction at
// least its scattering). Registered as the type's validator, so scene and preset loading, `--set`
// and sequences all run it; throws one welkin::Error whose path names the field ("/top_radius_km").
void validate(const Atmosphere& a);

}  // namespace welkin::atmosphere
