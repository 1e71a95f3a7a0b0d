#include "reference/transmittance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "reference/ray_geometry.h"
#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

using testing::constant_shell;
using testing::exponential_shell;
using testing::naive_visible_length;

constexpr double kR = 6360.0;
constexpr double kTop = 6460.0;

// Relative tolerance with the absolute floor the library promises for optical depths.
void expect_rel(const glm::dvec3& actual, const glm::dvec3& expected, double rel,
                double floor = kOpticalDepthTolerance.absolute_tolerance) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(actual[c], expected[c], std::max(rel * std::abs(expected[c]), floor))
        << "channel " << c;
  }
}

double tangent_mu(double sphere_radius, double r) {
  return -std::sqrt(1.0 - (sphere_radius / r) * (sphere_radius / r));
}

// Constant density: optical depth = sigma * visible chord length, chord by the textbook formula.
TEST(Transmittance, ConstantShellIsExpOfSigmaTimesChord) {
  const glm::dvec3 sigma(0.01, 0.02, 0.05);
  const AtmosphereModel m = constant_shell(sigma, kR, kTop);
  struct Case {
    double r, mu;
  };
  const double r50 = kR + 50.0, space = 7000.0;
  const std::vector<Case> cases = {
      {kR, 1.0},
      {kR, 0.5},
      {kR, 0.1},
      {kR, 0.01},
      {kR, 0.0},  // Last: grazing the ground.
      {r50, 0.3},
      {r50, -0.05},
      {r50, tangent_mu(kR, r50) + 1e-4},  // Limb: just misses the ground, longest chord.
      {r50, tangent_mu(kR, r50) - 1e-4},  // Just hits it.
      {space, -0.9},
      {space, -0.39},                           // From space: to the ground, through the limb.
      {space, tangent_mu(kTop, space) - 1e-6},  // Grazing the top from outside.
      {kTop, -0.01},
      {kTop, -0.5}};
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "r=" << c.r << " mu=" << c.mu);
    const double length = naive_visible_length(c.r, c.mu, kR, kTop);
    ASSERT_GT(length, 0.0);
    const QuadratureResult tau = optical_depth_to_boundary(m, c.r, c.mu);
    EXPECT_TRUE(tau.converged);
    expect_rel(tau.value, sigma * length, 1e-9);
    expect_rel(transmittance_to_boundary(m, c.r, c.mu), glm::exp(-sigma * length), 1e-9);
  }
}

TEST(Transmittance, RaysThatSeeNoAtmosphere) {
  const AtmosphereModel m = AtmosphereModel::earth();
  EXPECT_EQ(transmittance_to_boundary(m, 7000.0, 0.2), glm::dvec3(1.0));   // Leaving.
  EXPECT_EQ(transmittance_to_boundary(m, 7000.0, -0.3), glm::dvec3(1.0));  // Passing beside.
  EXPECT_EQ(transmittance_to_boundary(m, kR, -0.2), glm::dvec3(1.0));      // Ground at 0 km.
  EXPECT_EQ(transmittance_to_boundary(m, kTop, 0.0), glm::dvec3(1.0));     // Tangent at top.
  EXPECT_EQ(transmittance_to_boundary(m, kTop, 0.4), glm::dvec3(1.0));
}

TEST(Transmittance, CameraUnderGroundIsClampedToTheGround) {
  const AtmosphereModel m = AtmosphereModel::earth();
  for (double mu : {1.0, 0.3, 0.0, -0.4}) {
    EXPECT_EQ(transmittance_to_boundary(m, kR - 5.0, mu), transmittance_to_boundary(m, kR, mu));
  }
}

TEST(Transmittance, FromSpaceEqualsFromTheEntryPoint) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const double r = 9000.0;
  for (double mu : {-0.95, -0.7, -0.69}) {
    // Entry point by the textbook formula, then the same ray restarted from there.
    const double t = -r * mu - std::sqrt(r * r * mu * mu - (r * r - kTop * kTop));
    const glm::dvec3 origin(r, 0.0, 0.0), dir(mu, std::sqrt(1.0 - mu * mu), 0.0);
    const auto [r2, mu2] = radius_mu(origin + t * dir, dir);
    expect_rel(optical_depth_to_boundary(m, r, mu).value,
               optical_depth_to_boundary(m, r2, mu2).value, 1e-8);
  }
}

// Exponential profile, vertical rays: tau = sigma H (exp(-h0 / H) - exp(-h1 / H)).
TEST(Transmittance, ExponentialVerticalRayMatchesClosedForm) {
  const glm::dvec3 sigma(0.0058, 0.0136, 0.0331);
  for (double H : {8.0, 1.2, 0.05}) {
    const AtmosphereModel m = exponential_shell(sigma, H, kR, kTop);
    auto closed = [&](double h0, double h1) {
      return sigma * H * (std::exp(-h0 / H) - std::exp(-h1 / H));
    };
    SCOPED_TRACE(H);
    expect_rel(optical_depth_to_boundary(m, kR, 1.0).value, closed(0.0, 100.0), 1e-9);
    expect_rel(optical_depth_to_boundary(m, kR + 3.0, 1.0).value, closed(3.0, 100.0), 1e-9);
    expect_rel(optical_depth_to_boundary(m, kR + 50.0, -1.0).value, closed(0.0, 50.0), 1e-9);
    expect_rel(transmittance_between(m, kR + 2.0, 1.0, 7.0), glm::exp(-closed(2.0, 9.0)), 1e-9);
  }
}

// Horizontal rays through the full Earth model against a brute-force midpoint sum of 10^6 steps
// with the naive altitude sqrt(r^2 + s^2) - R.
TEST(Transmittance, HorizontalRayMatchesBruteForceMidpointSum) {
  const AtmosphereModel m = AtmosphereModel::earth();
  for (double h0 : {0.0, 10.0, 30.0}) {
    const double r = kR + h0;
    const double length = naive_visible_length(r, 0.0, kR, kTop);
    const int n = 1'000'000;
    const double ds = length / n;
    glm::dvec3 brute(0.0);
    for (int i = 0; i < n; ++i) {
      const double s = (i + 0.5) * ds;
      brute += m.extinction(std::sqrt(r * r + s * s) - kR) * ds;
    }
    SCOPED_TRACE(h0);
    expect_rel(optical_depth_to_boundary(m, r, 0.0).value, brute, 2e-8);
  }
}

TEST(Transmittance, SegmentsAddUp) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const double r = kR + 1.0, mu = -0.02;
  const glm::dvec3 whole = optical_depth(m, r, mu, 0.0, 300.0).value;
  const glm::dvec3 parts =
      optical_depth(m, r, mu, 0.0, 120.0).value + optical_depth(m, r, mu, 120.0, 300.0).value;
  expect_rel(parts, whole, 1e-9);
  // Past the ground hit nothing is added.
  const double end = atmosphere_interval(m, r, mu).end_km;
  EXPECT_EQ(optical_depth(m, r, mu, 0.0, end + 500.0).value,
            optical_depth(m, r, mu, 0.0, end).value);
}

TEST(Transmittance, MonotoneAlongRaysAndInUnitInterval) {
  const AtmosphereModel m = AtmosphereModel::earth();
  for (double r : {kR, kR + 20.0, kTop, 8000.0}) {
    for (double mu : {1.0, 0.2, 0.0, -0.05, -0.3, -0.6, -1.0}) {
      const RayInterval iv = atmosphere_interval(m, r, mu);
      glm::dvec3 previous(1.0);
      for (int i = 0; i <= 40; ++i) {
        const double d = iv.end_km * i / 40.0;
        const glm::dvec3 t = transmittance_between(m, r, mu, d);
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(t[c], 0.0);
          EXPECT_LE(t[c], previous[c] * (1.0 + 1e-12));
        }
        previous = t;
      }
    }
  }
}

TEST(Transmittance, SunBlockedByThePlanetOnlyBelowTheGeometricHorizon) {
  const AtmosphereModel m = AtmosphereModel::earth();
  EXPECT_EQ(transmittance_to_sun(m, kR, -0.01), glm::dvec3(0.0));
  EXPECT_GT(transmittance_to_sun(m, kR, 0.0).x, 0.0);  // Sun on the horizon: grazing.
  const double r = kR + 50.0;
  EXPECT_GT(transmittance_to_sun(m, r, tangent_mu(kR, r) + 1e-6).x, 0.0);
  EXPECT_EQ(transmittance_to_sun(m, r, tangent_mu(kR, r) - 1e-6), glm::dvec3(0.0));
  expect_rel(transmittance_to_sun(m, r, 0.3), transmittance_to_boundary(m, r, 0.3), 0.0);
}

TEST(Transmittance, DensityScaleZeroAndThousand) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const AtmosphereModel none = m.with_density_scale(0.0);
  const AtmosphereModel thick = m.with_density_scale(1000.0);
  for (double mu : {1.0, 0.0, -0.1}) {
    EXPECT_EQ(optical_depth_to_boundary(none, kR + 1.0, mu).value, glm::dvec3(0.0));
    EXPECT_EQ(transmittance_to_boundary(none, kR + 1.0, mu), glm::dvec3(1.0));
    expect_rel(optical_depth_to_boundary(thick, kR + 1.0, mu).value,
               1000.0 * optical_depth_to_boundary(m, kR + 1.0, mu).value, 1e-9);
    const glm::dvec3 t = transmittance_to_boundary(thick, kR + 1.0, mu);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(t[c] >= 0.0 && t[c] <= 1.0);
  }
}

// Scaling every length by k and every coefficient by 1/k leaves optical depths unchanged: checks
// the geometry on a 1 km and a 100 000 km planet against Earth.
TEST(Transmittance, TinyAndHugePlanetsAreScaleInvariant) {
  const AtmosphereModel earth = AtmosphereModel::earth();
  for (double bottom : {1.0, 100000.0}) {
    const double k = bottom / kR;
    const AtmosphereModel m = earth.scaled(k);
    for (double h : {0.0, 5.0, 60.0}) {
      for (double mu : {1.0, 0.1, 0.0, -0.1, tangent_mu(kR, kR + h) + 1e-5}) {
        SCOPED_TRACE(::testing::Message() << bottom << " " << h << " " << mu);
        expect_rel(optical_depth_to_boundary(m, (kR + h) * k, mu).value,
                   optical_depth_to_boundary(earth, kR + h, mu).value, 1e-8);
      }
    }
  }
  // Earth's 100 km atmosphere on a 1 km planet: finite, in [0, 1].
  AtmosphereModel tiny = earth;
  tiny.bottom_radius_km = 1.0;
  tiny.top_radius_km = 101.0;
  for (double mu : {1.0, 0.0, -0.5, -0.99}) {
    const glm::dvec3 t = transmittance_to_boundary(tiny, 1.0001, mu);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(t[c] > 0.0 && t[c] <= 1.0);
  }
}

// Tighter tolerances give smaller errors at more evaluations, and the requested tolerance bounds
// the true error. A 100 m scale height on a 200 km slant ray: most of the optical depth sits in
// the last few hundred metres, which the first Kronrod nodes resolve poorly.
TEST(Transmittance, ErrorShrinksAsToleranceTightens) {
  const AtmosphereModel m = exponential_shell(glm::dvec3(0.01, 0.02, 0.04), 0.1, kR, kTop);
  const double r = kTop, mu = -0.5;
  const glm::dvec3 exact =
      optical_depth_to_boundary(m, r, mu, {.relative_tolerance = 1e-14, .absolute_tolerance = 0})
          .value;
  std::vector<double> errors;
  int previous_evaluations = 0;
  for (double tol : {1e-1, 1e-3, 1e-5, 1e-9}) {
    const QuadratureResult q =
        optical_depth_to_boundary(m, r, mu, {.relative_tolerance = tol, .absolute_tolerance = 0});
    const double error = glm::length(q.value - exact) / glm::length(exact);
    SCOPED_TRACE(tol);
    EXPECT_LE(error, tol);
    EXPECT_LE(glm::length(q.value - exact), glm::length(q.error));  // Estimate is an upper bound.
    if (!errors.empty()) {
      EXPECT_LE(error, errors.back() + 1e-14);
    }
    EXPECT_GE(q.evaluations, previous_evaluations);
    errors.push_back(error);
    previous_evaluations = q.evaluations;
  }
  EXPECT_LT(errors.back(), 1e-3 * errors.front());
}

}  // namespace
}  // namespace welkin::atmosphere::reference
