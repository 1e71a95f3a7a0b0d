#include "welkin/atmosphere/stars.h"

#include <cmath>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>
#include <random>

namespace welkin::atmosphere {

void describe(TypeBuilder<Stars>& t) {
  t.tooltip("Procedural star field, fixed to the celestial sphere; shown while the sun is below the horizon");
  t.field("count", &Stars::count).range(0, 200000).tooltip("Stars down to the faintest magnitude");
  t.field("faintest_magnitude", &Stars::faintest_magnitude).range(-1, 12);
  t.field("brightness", &Stars::brightness).range(0, 1e6).tooltip("1: illuminance from magnitude");
  t.field("seed", &Stars::seed).range(0, 1 << 30);
  t.field("local_sidereal_time_deg", &Stars::local_sidereal_time_deg)
      .unit("deg")
      .range(-360, 720)
      .tooltip("Turns the sky; the time-of-day module sets it");
  t.field("latitude_deg", &Stars::latitude_deg).unit("deg").range(-90, 90);
}

std::vector<Star> make_star_catalogue(const Stars& s) {
  // Linear Rec.709 tints of blackbodies near each class's temperature, luminance 1, with the
  // classes' shares among naked-eye stars.
  struct SpectralClass {
    double share;
    glm::dvec3 tint;
  };
  static const SpectralClass kClasses[] = {{0.10, {0.62, 0.74, 1.30}}, {0.22, {0.78, 0.87, 1.17}},
                                           {0.19, {0.96, 0.98, 1.06}}, {0.14, {1.08, 0.99, 0.88}},
                                           {0.31, {1.30, 0.93, 0.60}}, {0.04, {1.62, 0.85, 0.38}}};
  std::mt19937_64 rng(std::uint64_t(s.seed) * 0x9E3779B97F4A7C15ull + 1);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Star> out;
  out.reserve(size_t(std::max(s.count, 0)));
  for (int i = 0; i < s.count; ++i) {
    const double z = 2.0 * uniform(rng) - 1.0, phi = 2.0 * M_PI * uniform(rng);
    const double q = std::sqrt(std::max(0.0, 1.0 - z * z));
    // N(< m) proportional to 10^(0.48 m) up to the faintest magnitude: invert its CDF.
    const double u = std::max(uniform(rng), 1e-300);
    const double magnitude = std::max(double(s.faintest_magnitude) + std::log10(u) / 0.48, -1.46);
    const double lux = 2.54e-6 * std::pow(10.0, -0.4 * magnitude) * s.brightness;
    double pick = uniform(rng);
    glm::dvec3 tint = kClasses[5].tint;
    for (const SpectralClass& c : kClasses) {
      if (pick < c.share) {
        tint = c.tint;
        break;
      }
      pick -= c.share;
    }
    tint /= glm::dot(tint, glm::dvec3(0.2126, 0.7152, 0.0722));
    out.push_back({.direction = glm::vec3(float(q * std::cos(phi)), float(q * std::sin(phi)), float(z)),
                   .illuminance_lux = float(lux),
                   .color = glm::vec3(tint)});
  }
  return out;
}

glm::dmat3 celestial_to_local(double local_sidereal_time_deg, double latitude_deg) {
  const double lst = glm::radians(local_sidereal_time_deg), lat = glm::radians(latitude_deg);
  const glm::dvec3 east(1, 0, 0);
  const glm::dvec3 meridian(0, -std::sin(lat), std::cos(lat));  // the equator on the meridian
  const glm::dvec3 pole(0, std::cos(lat), std::sin(lat));        // the celestial north pole
  // Hour angle H = LST - a: direction = cos d (cos H meridian - sin H east) + sin d pole, expanded in
  // cos a, sin a.
  return glm::dmat3(std::cos(lst) * meridian - std::sin(lst) * east,
                    std::sin(lst) * meridian + std::cos(lst) * east, pole);
}

}  // namespace welkin::atmosphere
