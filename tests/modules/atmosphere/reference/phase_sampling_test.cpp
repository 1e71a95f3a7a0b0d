#include "reference/phase_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/geometric.hpp>
#include <vector>

#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

using testing::gauss_legendre_5;

// Small deterministic generator for the test (splitmix64), independent of the library's.
class TestRng {
 public:
  explicit TestRng(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

// Mass of a density over [a, b], with pieces graded towards an end at +-1 where peaks live.
double mass(const std::function<double(double)>& density, double a, double b) {
  if (b < 1.0 && a > -1.0) return gauss_legendre_5(density, a, b, 16);
  double sum = 0.0, lo = a, hi = b;
  for (int k = 0; k < 45; ++k) {
    if (b >= 1.0) {
      const double mid = 1.0 - (1.0 - lo) * 0.5;
      sum += gauss_legendre_5(density, lo, mid, 2);
      lo = mid;
    } else {
      const double mid = -1.0 + (hi + 1.0) * 0.5;
      sum += gauss_legendre_5(density, mid, hi, 2);
      hi = mid;
    }
  }
  return sum + (b >= 1.0 ? gauss_legendre_5(density, lo, 1.0, 1)
                         : gauss_legendre_5(density, -1.0, hi, 1));
}

// Histogram of weighted cosines about `axis` against the density's mass per bin: each bin within
// 5 standard errors. Also checks unit length and that azimuths average out.
void expect_distribution(
    const std::function<PhaseSample(const glm::dvec3&, double, double)>& sample,
    const std::function<double(double)>& cos_density, double lo = -1.0) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const int n = 400'000, bins = 20;
  std::vector<double> sum(bins, 0.0), sum_sq(bins, 0.0);
  glm::dvec3 perpendicular_mean(0.0);
  TestRng rng(7);
  for (int i = 0; i < n; ++i) {
    const double xi = rng.uniform();
    const PhaseSample s = sample(axis, xi, rng.uniform());
    ASSERT_NEAR(glm::length(s.direction), 1.0, 1e-12);
    const double mu = glm::dot(s.direction, axis);
    ASSERT_GE(mu, lo - 1e-12);
    perpendicular_mean += (s.direction - mu * axis) / double(n);
    const int bin = std::min(bins - 1, static_cast<int>((mu - lo) / (1.0 - lo) * bins));
    sum[bin] += s.weight;
    sum_sq[bin] += s.weight * s.weight;
  }
  for (int b = 0; b < bins; ++b) {
    const double a = lo + (1.0 - lo) * b / bins, c = lo + (1.0 - lo) * (b + 1) / bins;
    const double expected = mass(cos_density, a, c);
    const double observed = sum[b] / n;
    const double standard_error = std::sqrt(std::max(sum_sq[b] / n - observed * observed, 0.0) / n);
    EXPECT_NEAR(observed, expected, 5.0 * standard_error + 1e-6) << "bin " << b;
  }
  EXPECT_LT(glm::length(perpendicular_mean), 5.0 / std::sqrt(double(n)));
}

TEST(PhaseSampling, RayleighMatchesItsPhaseFunction) {
  expect_distribution(
      [](const glm::dvec3& axis, double u, double v) { return sample_rayleigh(axis, u, v); },
      [](double mu) { return 2.0 * kPi * rayleigh_phase(mu); });
}

TEST(PhaseSampling, MieMatchesHenyeyGreensteinAndCornetteShanks) {
  for (double g : {0.8, -0.5, 0.999, 0.0}) {
    for (MiePhase phase : {MiePhase::henyey_greenstein, MiePhase::cornette_shanks}) {
      AtmosphereModel m = AtmosphereModel::earth();
      m.mie_g = g;
      m.mie_phase = phase;
      SCOPED_TRACE(::testing::Message() << g << " " << static_cast<int>(phase));
      expect_distribution(
          [&](const glm::dvec3& axis, double u, double v) { return sample_mie(m, axis, u, v); },
          [&](double mu) { return 2.0 * kPi * m.mie_phase_value(mu); });
    }
  }
}

TEST(PhaseSampling, CosineHemisphereHasDensityTwoMu) {
  expect_distribution(
      [](const glm::dvec3& axis, double u, double v) {
        return PhaseSample{sample_cosine_hemisphere(axis, u, v), 1.0};
      },
      [](double mu) { return 2.0 * mu; }, 0.0);
}

TEST(PhaseSampling, DirectionAboutAxisKeepsTheRequestedAngle) {
  for (const glm::dvec3 axis : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0),
                                glm::normalize(glm::dvec3(-0.2, 0.7, -0.1))}) {
    for (double c : {-1.0, -0.3, 0.0, 0.9, 1.0}) {
      EXPECT_NEAR(glm::dot(direction_about(axis, c, 1.234), axis), c, 1e-12);
    }
  }
}

}  // namespace
}  // namespace welkin::atmosphere::reference
