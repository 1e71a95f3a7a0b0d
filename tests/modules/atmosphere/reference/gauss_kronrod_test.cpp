#include "reference/gauss_kronrod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace welkin::atmosphere::reference {
namespace {

QuadratureResult integrate(auto f, std::vector<double> points, QuadratureSettings s = {}) {
  return integrate_gauss_kronrod(f, std::span<const double>(points), s);
}

TEST(GaussKronrod, ExactForPolynomialsUpToDegree22InOnePass) {
  // One 15-point Kronrod rule integrates x^k exactly for k <= 22 (and G7 for k <= 13, so the
  // error estimate vanishes there too): int_0^1 x^k = 1 / (k + 1).
  for (int k : {0, 1, 5, 13, 22}) {
    const QuadratureResult q =
        integrate([k](double x) { return glm::dvec3(std::pow(x, k), 2.0 * std::pow(x, k), 0.0); },
                  {0, 1}, {.relative_tolerance = 1.0});
    EXPECT_NEAR(q.value.x, 1.0 / (k + 1), 1e-15) << k;
    EXPECT_NEAR(q.value.y, 2.0 / (k + 1), 2e-15) << k;
    EXPECT_EQ(q.evaluations, 15);
  }
}

TEST(GaussKronrod, AdaptsToEndpointSingularityAndMeetsTolerance) {
  for (double tol : {1e-4, 1e-8, 1e-12}) {
    const QuadratureResult q =
        integrate([](double x) { return glm::dvec3(std::sqrt(x), 1.0 / std::sqrt(x + 1e-6), 0.0); },
                  {0.0, 1.0}, {.relative_tolerance = tol, .absolute_tolerance = 0.0});
    EXPECT_TRUE(q.converged);
    EXPECT_NEAR(q.value.x, 2.0 / 3.0, tol * 2.0 / 3.0);
    const double exact_y = 2.0 * (std::sqrt(1.0 + 1e-6) - std::sqrt(1e-6));
    EXPECT_NEAR(q.value.y, exact_y, tol * exact_y);
    EXPECT_LE(q.error.x, tol * q.value.x);
  }
}

TEST(GaussKronrod, BreakpointsMakeJumpsExact) {
  auto step = [](double x) { return glm::dvec3(x < 0.3 ? 1.0 : 5.0); };
  const QuadratureResult split = integrate(step, {0.0, 0.3, 1.0});
  EXPECT_EQ(split.evaluations, 30);
  EXPECT_NEAR(split.value.x, 0.3 + 3.5, 1e-15);
  // Without the breakpoint the jump is found by bisection, at a cost.
  const QuadratureResult blind = integrate(step, {0.0, 1.0});
  EXPECT_NEAR(blind.value.x, 3.8, 1e-8);
  EXPECT_GT(blind.evaluations, 200);
}

TEST(GaussKronrod, ReportsNonConvergenceAtTheIntervalLimit) {
  const QuadratureResult q = integrate([](double x) { return glm::dvec3(std::sin(1.0 / x)); },
                                       {1e-9, 1.0}, {.max_intervals = 20});
  EXPECT_FALSE(q.converged);
  EXPECT_TRUE(std::isfinite(q.value.x));
}

TEST(GaussKronrod, EmptyAndZeroIntegrands) {
  EXPECT_EQ(integrate([](double) { return glm::dvec3(1.0); }, {2.0, 2.0}).value, glm::dvec3(0.0));
  const QuadratureResult zero = integrate([](double) { return glm::dvec3(0.0); }, {0.0, 1.0});
  EXPECT_TRUE(zero.converged);
  EXPECT_EQ(zero.evaluations, 15);
}

}  // namespace
}  // namespace welkin::atmosphere::reference
