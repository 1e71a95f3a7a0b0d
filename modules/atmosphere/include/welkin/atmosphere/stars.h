// A procedural star field for the night sky: stars spread uniformly over the celestial sphere with
// the naked-eye magnitude distribution and the tints of the main spectral classes, fixed to the sky
// and turned by the local sidereal time (the time-of-day module sets it and the latitude).
#pragma once

#include <glm/mat3x3.hpp>
#include <string_view>
#include <vector>

#include "welkin/atmosphere/gpu_blocks.h"
#include "welkin/core/reflection.h"

namespace welkin::atmosphere {

struct Stars {
  static constexpr std::string_view kTypeName = "atmosphere.Stars";
  int count = 9000;                // stars down to faintest_magnitude (about 9000 to 6.5 by eye)
  float faintest_magnitude = 6.5f;
  float brightness = 1.0f;         // 1: each star's illuminance from its magnitude (physical)
  int seed = 1;
  float local_sidereal_time_deg = 0.0f;
  float latitude_deg = 46.5f;
};
void describe(TypeBuilder<Stars>& t);

// The stars as the shader's storage buffer reads them (Star: gpu_blocks.h), deterministic for a given
// count, seed, faintest magnitude and brightness. Magnitudes follow the observed counts, about three
// times as many stars per magnitude fainter (N(<m) ~ 10^(0.48 m)), with illuminance
// 2.54e-6 lux x 10^(-0.4 m), no star brighter than Sirius (-1.46).
std::vector<Star> make_star_catalogue(const Stars& stars);

// Rotation from the celestial frame to the scene's (x east, y north, z up) at a latitude and local
// sidereal time: a star at right ascension a and declination d has hour angle LST - a.
glm::dmat3 celestial_to_local(double local_sidereal_time_deg, double latitude_deg);

}  // namespace welkin::atmosphere
