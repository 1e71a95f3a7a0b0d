#include "reference/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "test_support.h"

namespace welkin::clouds::reference {
namespace {

using testing::direction_deg;

// Single scattering of a homogeneous slab [0, H] in closed form (van de Hulst; Prahl 1988 eqs.
// 3.30, 3.32): mu_v = |view.z|, mu_s = sun.z > 0. Reflection: camera above, looking down.
double slab_single_reflection(double albedo, double tau, double phase, double mu_v, double mu_s) {
  const double k = 1.0 / mu_v + 1.0 / mu_s;
  return albedo * phase / mu_v * (1.0 - std::exp(-tau * k)) / k;
}
// Transmission: camera below, looking up (mu_v != mu_s).
double slab_single_transmission(double albedo, double tau, double phase, double mu_v, double mu_s) {
  const double k = 1.0 / mu_v - 1.0 / mu_s;
  return albedo * phase / mu_v * std::exp(-tau / mu_s) * -std::expm1(-tau * k) / k;
}

TEST(Quadrature, AdaptiveRuleOnSmoothAndPeakedIntegrands) {
  EXPECT_NEAR(integrate_adaptive([](double x) { return std::sin(x); }, 0.0, kPi), 2.0, 1e-13);
  EXPECT_NEAR(integrate_adaptive([](double x) { return 1e4 * std::exp(-1e4 * x); }, 0.0, 1.0),
              -std::expm1(-1e4), 1e-9);
  EXPECT_EQ(integrate_adaptive([](double) { return 1.0; }, 2.0, 1.0), 0.0);
}

// (a) Transmittance of a homogeneous slab is exp(-sigma_t L), to 1e-9 and better.
TEST(Quadrature, SlabTransmittanceIsBeerLambert) {
  const HomogeneousSlab slab(1000.0, 1800.0, 0.004);
  for (const double zenith : {0.0, 30.0, 60.0, 85.0}) {
    const Ray ray{{3.0, -2.0, 0.0}, direction_deg(zenith, 40.0)};
    const double length = 800.0 / std::cos(zenith * kPi / 180.0);
    EXPECT_NEAR(optical_depth(slab, ray, 0.0, kInfinity), 0.004 * length, 1e-12 * length);
    const double expected = std::exp(-0.004 * length);
    EXPECT_NEAR(transmittance(slab, ray), expected, 1e-9 * expected) << zenith;
  }
  // Partial stretches and a ray that never enters.
  const Ray up{{0, 0, 0}, {0, 0, 1}};
  EXPECT_NEAR(optical_depth(slab, up, 1200.0, 1500.0), 0.004 * 300.0, 1e-13);
  EXPECT_EQ(transmittance(slab, {{0, 0, 0}, {0, 0, -1}}), 1.0);
  // Horizontal inside the slab: infinitely deep.
  EXPECT_EQ(transmittance(slab, {{0, 0, 1400}, {1, 0, 0}}), 0.0);
}

TEST(Quadrature, SphereChordAndSmoothFunctionMedium) {
  const HomogeneousSphere sphere({0, 0, 0}, 500.0, 0.01);
  EXPECT_NEAR(transmittance(sphere, {{300, 0, -2000}, {0, 0, 1}}), std::exp(-0.01 * 800.0), 1e-14);
  // Exponential density sigma0 exp(-z / H) between z = 0 and 5 km, vertical ray: closed form.
  const double sigma0 = 0.002, scale = 700.0;
  const FunctionMedium exponential(
      [&](const glm::dvec3& p) { return p.z >= 0.0 && p.z <= 5000.0 ? sigma0 * std::exp(-p.z / scale) : 0.0; },
      [&](const Ray& r) { return HomogeneousSlab(0.0, 5000.0, sigma0).segments(r); });
  const double depth = sigma0 * scale * -std::expm1(-5000.0 / scale);
  EXPECT_NEAR(optical_depth(exponential, {{0, 0, 0}, {0, 0, 1}}, 0.0, kInfinity), depth, 1e-10 * depth);
}

// Single scattering of homogeneous slabs against the closed form, thin (tau = 1e-3) and thick
// (tau = 5), reflected and transmitted, relative 1e-9; and a camera inside the slab.
TEST(Quadrature, SlabSingleScatteringMatchesClosedForm) {
  const HenyeyGreenstein phase(0.6);
  const Lighting lighting{.sun_direction = direction_deg(35.0, 0.0), .sun_irradiance = 2.0};
  const double mu_s = std::cos(35.0 * kPi / 180.0);
  for (const double tau : {1e-3, 5.0}) {
    const HomogeneousSlab slab(0.0, 500.0, tau / 500.0, 0.9);
    const glm::dvec3 down = direction_deg(180.0 - 50.0, 120.0), up = direction_deg(20.0, 70.0);
    const double mu_down = std::cos(50.0 * kPi / 180.0), mu_up = std::cos(20.0 * kPi / 180.0);
    const SingleScatteringResult reflected = single_scattering(slab, phase, {{0, 0, 800}, down}, lighting);
    const double expected_r =
        2.0 * slab_single_reflection(0.9, tau, phase.evaluate(glm::dot(down, lighting.sun_direction)), mu_down, mu_s);
    EXPECT_NEAR(reflected.radiance, expected_r, 1e-9 * expected_r) << tau;
    EXPECT_NEAR(reflected.transmittance, std::exp(-tau / mu_down), 1e-12) << tau;
    const SingleScatteringResult transmitted = single_scattering(slab, phase, {{0, 0, -50}, up}, lighting);
    const double expected_t =
        2.0 * slab_single_transmission(0.9, tau, phase.evaluate(glm::dot(up, lighting.sun_direction)), mu_up, mu_s);
    EXPECT_NEAR(transmitted.radiance, expected_t, 1e-9 * expected_t) << tau;
  }
  // Camera at mid-height looking down: the lower half only, as a slab of half the depth whose
  // top lies under an extra optical depth tau / 2 towards the sun.
  const double tau = 2.0;
  const HomogeneousSlab slab(0.0, 500.0, tau / 500.0);
  const glm::dvec3 down = direction_deg(180.0 - 30.0, 0.0);
  const double mu_v = std::cos(30.0 * kPi / 180.0);
  const double p = phase.evaluate(glm::dot(down, lighting.sun_direction));
  const double expected = 2.0 * std::exp(-0.5 * tau / mu_s) * slab_single_reflection(1.0, 0.5 * tau, p, mu_v, mu_s);
  EXPECT_NEAR(single_scattering(slab, phase, {{0, 0, 250}, down}, lighting).radiance, expected, 1e-9 * expected);
}

// (e) Stiff: extinction x0 gives the background exactly; x1000 (tau = 5000) stays finite and
// matches the closed form of a deep slab; the sun below an opaque slab gives nothing below it.
TEST(Quadrature, StiffExtinction) {
  const HenyeyGreenstein phase(0.8);
  const Lighting lighting{.sun_direction = direction_deg(20.0, 0.0), .sky_radiance = 0.3, .ground_radiance = 0.3};
  const Ray down{{0, 0, 600}, direction_deg(140.0, 0.0)};
  const SingleScatteringResult empty = single_scattering(HomogeneousSlab(0.0, 500.0, 0.0), phase, down, lighting);
  EXPECT_EQ(empty.radiance, 0.0);
  EXPECT_EQ(empty.transmittance, 1.0);
  EXPECT_EQ(empty.background, 0.3);

  const HomogeneousSlab dense(0.0, 500.0, 10.0);  // tau = 5000.
  const SingleScatteringResult r = single_scattering(dense, phase, down, lighting);
  const double mu_v = std::cos(40.0 * kPi / 180.0), mu_s = std::cos(20.0 * kPi / 180.0);
  const double expected =
      slab_single_reflection(1.0, 5000.0, phase.evaluate(glm::dot(down.direction, lighting.sun_direction)), mu_v, mu_s);
  ASSERT_TRUE(std::isfinite(r.radiance));
  EXPECT_NEAR(r.radiance, expected, 1e-8 * expected);
  EXPECT_EQ(r.transmittance, 0.0);
  EXPECT_EQ(r.background, 0.0);
  const SingleScatteringResult below = single_scattering(dense, phase, {{0, 0, -10}, {0, 0, 1}}, lighting);
  EXPECT_EQ(below.radiance, 0.0);
}

// Error shrinks as the tolerance tightens on a field with structure (sinusoidal density).
TEST(Quadrature, ErrorShrinksWithTolerance) {
  const FunctionMedium wavy(
      [](const glm::dvec3& p) {
        return p.z >= 0.0 && p.z <= 1000.0 ? 0.002 * (1.0 + std::sin(p.z / 37.0)) : 0.0;
      },
      [](const Ray& r) { return HomogeneousSlab(0.0, 1000.0, 0.004).segments(r); });
  const double exact = 0.002 * (1000.0 + 37.0 * (1.0 - std::cos(1000.0 / 37.0)));
  double previous = kInfinity;
  for (const double tol : {1e-2, 1e-5, 1e-8, 1e-11}) {
    const double error =
        std::abs(optical_depth(wavy, {{0, 0, -1}, {0, 0, 1}}, 0.0, kInfinity, {.relative_tolerance = tol}) - exact);
    EXPECT_LE(error, std::max(previous, 1e-13));
    EXPECT_LT(error, 10.0 * tol * exact + 1e-13) << tol;
    previous = error;
  }
}

}  // namespace
}  // namespace welkin::clouds::reference
