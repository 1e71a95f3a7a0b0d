#include "reference/phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <memory>
#include <string>
#include <vector>

#include "reference/medium.h"
#include "test_support.h"

namespace welkin::clouds::reference {
namespace {

using testing::integrate_cosine;

struct NamedPhase {
  std::string name;
  std::shared_ptr<PhaseFunction> phase;
};

std::vector<NamedPhase> all_phases() {
  return {{"isotropic", std::make_shared<HenyeyGreenstein>(0.0)},
          {"HG 0.85", std::make_shared<HenyeyGreenstein>(0.85)},
          {"HG -0.4", std::make_shared<HenyeyGreenstein>(-0.4)},
          {"HG 0.999", std::make_shared<HenyeyGreenstein>(0.999)},
          {"HG -0.999", std::make_shared<HenyeyGreenstein>(-0.999)},
          {"dual lobe takram", std::make_shared<DualLobeHenyeyGreenstein>()},
          {"dual lobe 0.999/-0.999", std::make_shared<DualLobeHenyeyGreenstein>(0.999, -0.999, 0.3)},
          {"Draine 0.5 alpha 22", std::make_shared<Draine>(0.5, 22.0)},
          {"Rayleigh as Draine", std::make_shared<Draine>(0.0, 1.0)},
          {"approximate Mie 5 um", std::make_shared<ApproximateMie>(5.0)},
          {"approximate Mie 10 um", std::make_shared<ApproximateMie>(10.0)},
          {"approximate Mie 50 um", std::make_shared<ApproximateMie>(50.0)}};
}

TEST(Phase, EachIntegratesToOneOverTheSphere) {
  for (const NamedPhase& p : all_phases()) {
    const double total = 2.0 * kPi * integrate_cosine([&](double mu) { return p.phase->evaluate(mu); });
    EXPECT_NEAR(total, 1.0, 1e-6) << p.name;
  }
}

TEST(Phase, MeanCosineMatchesClosedForm) {
  for (const NamedPhase& p : all_phases()) {
    const double mean = 2.0 * kPi * integrate_cosine([&](double mu) { return mu * p.phase->evaluate(mu); });
    EXPECT_NEAR(mean, p.phase->mean_cosine(), 1e-6) << p.name;
  }
  EXPECT_NEAR(DualLobeHenyeyGreenstein().mean_cosine(), 0.25, 1e-15);  // 0.5 * 0.7 + 0.5 * -0.2.
}

TEST(Phase, KnownValues) {
  EXPECT_NEAR(HenyeyGreenstein(0.0).evaluate(0.3), 1.0 / (4.0 * kPi), 1e-15);
  // Rayleigh: 3 (1 + mu^2) / (16 pi).
  EXPECT_NEAR(Draine(0.0, 1.0).evaluate(0.5), 3.0 * 1.25 / (16.0 * kPi), 1e-15);
  // Forward peak of HG: (1 + g) / ((1 - g)^2 4 pi), finite at g = 0.999.
  const double peak = HenyeyGreenstein(0.999).evaluate(1.0);
  EXPECT_TRUE(std::isfinite(peak));
  EXPECT_NEAR(peak, 1.999 / (1e-6 * 4.0 * kPi), 1e-6 * peak);
  for (const double g : {0.999, -0.999}) {
    for (const double mu : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      const double v = HenyeyGreenstein(g).evaluate(mu);
      EXPECT_TRUE(std::isfinite(v) && v > 0.0) << g << " " << mu;
    }
  }
}

// The fit's parameters at 10 um, recomputed here from Jendersie & d'Eon 2023's formulas, and the
// range check.
TEST(Phase, ApproximateMieParametersAt10Microns) {
  const ApproximateMieParameters p = approximate_mie_parameters(10.0);
  EXPECT_NEAR(p.g_hg, std::exp(-0.0990567 / 8.32846), 1e-15);
  EXPECT_NEAR(p.g_draine, std::exp(-2.20679 / 13.91029 - 0.428934), 1e-15);
  EXPECT_NEAR(p.alpha, std::exp(3.62489 - 8.29288 / 15.52825), 1e-12);
  EXPECT_NEAR(p.w_draine, std::exp(-0.599085 / 9.358417 - 0.665888), 1e-15);
  EXPECT_NEAR(p.g_hg, 0.988, 1e-3);  // A sharp forward lobe...
  EXPECT_NEAR(p.alpha, 22.0, 0.1);   // ... and a broad Draine lobe with a backward glory.
  EXPECT_THROW(approximate_mie_parameters(4.0), std::invalid_argument);
  EXPECT_THROW(approximate_mie_parameters(51.0), std::invalid_argument);
  EXPECT_THROW(Draine(0.3, -2.0), std::invalid_argument);
}

// Mass of a density over [lo, hi], graded towards an end of [-1, 1] where peaks live.
double bin_mass(const std::function<double(double)>& f, double lo, double hi) {
  const auto nodes = testing::gauss_legendre(16, -1.0, 1.0);
  auto piece = [&](double a, double b) {
    double sum = 0.0;
    for (const auto& [x, w] : nodes) sum += 0.5 * (b - a) * w * f(0.5 * (a + b) + 0.5 * (b - a) * x);
    return sum;
  };
  if (lo > -1.0 && hi < 1.0) return piece(lo, 0.5 * (lo + hi)) + piece(0.5 * (lo + hi), hi);
  double sum = 0.0, a = lo, b = hi;
  for (int k = 0; k < 50; ++k) {  // Halve the distance to the end each time.
    if (hi >= 1.0) {
      const double mid = 0.5 * (a + 1.0);
      sum += piece(a, mid);
      a = mid;
    } else {
      const double mid = 0.5 * (b - 1.0);
      sum += piece(mid, b);
      b = mid;
    }
  }
  return sum + (hi >= 1.0 ? piece(a, 1.0) : piece(-1.0, b));
}

// Histogram of sampled cosines against each bin's mass by quadrature: within 5 standard errors
// (a multinomial bin count), plus unit length and an azimuth that averages out.
TEST(Phase, SamplingMatchesEvaluate) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.2, -0.7, 0.4));
  const int n = 200'000, bins = 24;
  for (const NamedPhase& p : all_phases()) {
    RandomStream rng(11, 3);
    std::vector<int> counts(bins, 0);
    glm::dvec3 perpendicular(0.0);
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 d = p.phase->sample_direction(axis, rng);
      ASSERT_NEAR(glm::length(d), 1.0, 1e-12) << p.name;
      const double mu = glm::dot(d, axis);
      perpendicular += (d - mu * axis) / double(n);
      ++counts[std::clamp(static_cast<int>((mu + 1.0) * 0.5 * bins), 0, bins - 1)];
    }
    for (int b = 0; b < bins; ++b) {
      const double lo = -1.0 + 2.0 * b / bins, hi = -1.0 + 2.0 * (b + 1) / bins;
      const double mass = 2.0 * kPi * bin_mass([&](double mu) { return p.phase->evaluate(mu); }, lo, hi);
      const double observed = counts[b] / double(n);
      const double sigma = std::sqrt(std::max(mass * (1.0 - mass), 1e-12) / n);
      EXPECT_NEAR(observed, mass, 5.0 * sigma + 1e-9) << p.name << " bin " << b;
    }
    EXPECT_LT(glm::length(perpendicular), 5.0 / std::sqrt(double(n))) << p.name;
  }
}

}  // namespace
}  // namespace welkin::clouds::reference
