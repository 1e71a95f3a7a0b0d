#include "reference/cloud_path_tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "reference/quadrature.h"
#include "reference/tracking.h"
#include "test_support.h"

namespace welkin::clouds::reference {
namespace {

using testing::direction_deg;

PathTraceSettings with_samples(std::uint64_t samples, int max_orders = 1000) {
  PathTraceSettings s;
  s.samples = samples;
  s.max_orders = max_orders;
  return s;
}

// (a) Ratio tracking's mean transmittance is exp(-sigma L) within its CI, in one stretch and
// through a sphere; the estimator itself is also called directly.
TEST(CloudPathTracer, RatioTrackingTransmittanceIsBeerLambert) {
  const HenyeyGreenstein phase(0.0);
  const HomogeneousSlab slab(100.0, 400.0, 0.005);
  const Ray view{{0, 0, 0}, direction_deg(40.0, 10.0)};
  const double expected = std::exp(-0.005 * 300.0 / std::cos(40.0 * kPi / 180.0));
  const CloudRadianceEstimate r = path_trace(slab, phase, view, {}, with_samples(20'000, 1));
  EXPECT_NEAR(r.transmittance.mean, expected, 2.5 * r.transmittance.ci95);
  EXPECT_LT(r.transmittance.ci95, 0.05 * expected);

  RandomStream rng(5, 0);
  TrackingBudget budget;
  double sum = 0.0;
  const int n = 50'000;
  const HomogeneousSphere sphere({0, 0, 0}, 100.0, 0.02);  // Chord 200 m through the centre.
  for (int i = 0; i < n; ++i) sum += ratio_tracking_transmittance(sphere, {{0, 0, -500}, {0, 0, 1}}, kInfinity, rng, budget);
  // Each estimate is 0 or 0.1 (roulette) or a product in (0.1, 1]: bounded, so 5 / sqrt(n) is generous.
  EXPECT_NEAR(sum / n, std::exp(-4.0), 5.0 * 0.1 / std::sqrt(double(n)));
  EXPECT_EQ(budget.majorant_violations, 0u);
}

// First order of the path tracer (NEE with ratio-tracked shadow rays) against the single-scattering
// quadrature in a slab of optical depth 2, from outside and from inside a sphere (camera in the
// medium), within 2.5 CI95 half-widths (about 5 sigma).
TEST(CloudPathTracer, FirstOrderAgreesWithSingleScatteringQuadrature) {
  const DualLobeHenyeyGreenstein phase;
  const Lighting lighting{.sun_direction = direction_deg(40.0, 180.0)};
  const HomogeneousSlab slab(0.0, 400.0, 0.005, 0.95);
  const HomogeneousSphere sphere({0, 0, 0}, 300.0, 0.004);
  struct Case {
    const Medium* medium;
    Ray view;
  };
  for (const Case& c : {Case{&slab, {{0, 0, 500}, direction_deg(130.0, 30.0)}},
                        Case{&slab, {{0, 0, -20}, direction_deg(10.0, 0.0)}},
                        Case{&sphere, {{0, 0, 0}, direction_deg(70.0, 90.0)}},
                        Case{&sphere, {{0, 0, 0}, direction_deg(180.0, 0.0)}}}) {
    const CloudRadianceEstimate pt = path_trace(*c.medium, phase, c.view, lighting, with_samples(40'000, 1));
    const SingleScatteringResult ss = single_scattering(*c.medium, phase, c.view, lighting);
    EXPECT_EQ(pt.truncated_paths, 0u);
    EXPECT_LT(pt.scattered.ci95, 0.05 * ss.radiance);
    EXPECT_NEAR(pt.scattered.mean, ss.radiance, 2.5 * pt.scattered.ci95);
    EXPECT_NEAR(pt.transmittance.mean, ss.transmittance, 2.5 * pt.transmittance.ci95 + 1e-12);
  }
}

// (c) Optically thin slab (tau = 1e-3): single scattering in closed form, the path tracer at one
// order within its CI, and at all orders within its CI plus the second order's bound (~tau).
TEST(CloudPathTracer, ThinSlabMatchesClosedFormSingleScattering) {
  const double tau = 1e-3, mu_s = std::cos(30.0 * kPi / 180.0), mu_v = std::cos(45.0 * kPi / 180.0);
  const HomogeneousSlab slab(1000.0, 1500.0, tau / 500.0);
  const HenyeyGreenstein phase(0.5);
  const Lighting lighting{.sun_direction = direction_deg(30.0, 0.0)};
  const Ray view{{0, 0, 2000}, direction_deg(135.0, 0.0)};
  const double p = phase.evaluate(glm::dot(view.direction, lighting.sun_direction));
  const double k = 1.0 / mu_v + 1.0 / mu_s;
  const double closed_form = p / mu_v * -std::expm1(-tau * k) / k;
  EXPECT_NEAR(single_scattering(slab, phase, view, lighting).radiance, closed_form, 1e-9 * closed_form);
  const CloudRadianceEstimate first = path_trace(slab, phase, view, lighting, with_samples(1'500'000, 1));
  EXPECT_LT(first.scattered.ci95, 0.07 * closed_form);
  EXPECT_NEAR(first.scattered.mean, closed_form, 2.5 * first.scattered.ci95);
  const CloudRadianceEstimate all = path_trace(slab, phase, view, lighting, with_samples(1'500'000));
  EXPECT_NEAR(all.scattered.mean, closed_form, 2.5 * all.scattered.ci95 + 4.0 * tau * closed_form);
}

// White furnace: a conservative medium under a uniform sky of radiance 1 and no sun looks exactly
// like the sky from every direction: scattered + background = 1.
TEST(CloudPathTracer, WhiteFurnace) {
  const HenyeyGreenstein phase(0.7);
  const HomogeneousSphere cloud({0, 0, 0}, 200.0, 0.01);  // Optical diameter 4.
  const Lighting sky_only{.sun_irradiance = 0.0, .sky_radiance = 1.0, .ground_radiance = 1.0};
  for (const Ray view : {Ray{{0, 0, -1000}, {0, 0, 1}}, Ray{{50, 0, 0}, direction_deg(60.0, 30.0)}}) {
    const CloudRadianceEstimate r = path_trace(cloud, phase, view, sky_only, with_samples(20'000));
    EXPECT_EQ(r.truncated_paths, 0u);
    const double ci = std::hypot(r.scattered.ci95, r.background.ci95);
    EXPECT_NEAR(r.radiance(), 1.0, 2.5 * ci);
    EXPECT_LT(ci, 0.02);
  }
  // Single order: sky scattered once, still at most the sky.
  const CloudRadianceEstimate once = path_trace(cloud, phase, {{0, 0, -1000}, {0, 0, 1}}, sky_only, with_samples(20'000, 1));
  EXPECT_LT(once.radiance(), 1.0);
  EXPECT_GT(once.scattered.mean, 0.0);
}

// The sky and the ground apart: with no medium a ray sees the sky above the ground's horizon and
// the ground below it (flat, and a planet 6360 km across seen from 2 km up: its horizon is 1.44
// degrees down); through a cloud, what the sky alone and the ground alone give adds up to the white
// furnace's 1 (transport is linear in the light).
TEST(CloudPathTracer, SkyAndGroundApart) {
  const HenyeyGreenstein phase(0.7);
  const Lighting flat{.sun_irradiance = 0.0, .sky_radiance = 1.0, .ground_radiance = 0.25};
  const HomogeneousSlab empty(0.0, 500.0, 0.0);
  EXPECT_EQ(path_trace(empty, phase, {{0, 0, 600}, direction_deg(89.0, 0.0)}, flat, with_samples(10)).radiance(), 1.0);
  EXPECT_EQ(path_trace(empty, phase, {{0, 0, 600}, direction_deg(91.0, 0.0)}, flat, with_samples(10)).radiance(), 0.25);
  const double radius = 6360e3, dip = std::acos(radius / (radius + 2000.0)) * 180.0 / kPi;
  Lighting planet = flat;
  planet.planet_center_m = {0.0, 0.0, -radius - 2000.0}, planet.planet_radius_m = radius;
  EXPECT_NEAR(dip, 1.4358, 1e-3);
  EXPECT_EQ(path_trace(empty, phase, {{0, 0, 0}, direction_deg(90.0 + dip - 0.01, 0.0)}, planet, with_samples(10)).radiance(), 1.0);
  EXPECT_EQ(path_trace(empty, phase, {{0, 0, 0}, direction_deg(90.0 + dip + 0.01, 0.0)}, planet, with_samples(10)).radiance(), 0.25);

  const HomogeneousSphere cloud({0, 0, 0}, 200.0, 0.01);
  const Ray view{{50, 0, 0}, direction_deg(60.0, 30.0)};
  const Lighting sky{.sun_irradiance = 0.0, .sky_radiance = 1.0}, ground{.sun_irradiance = 0.0, .ground_radiance = 1.0};
  const CloudRadianceEstimate a = path_trace(cloud, phase, view, sky, with_samples(20'000));
  PathTraceSettings other_seed = with_samples(20'000);
  other_seed.seed = 2;
  const CloudRadianceEstimate b = path_trace(cloud, phase, view, ground, other_seed);
  const double ci = std::hypot(std::hypot(a.scattered.ci95, a.background.ci95), b.scattered.ci95);
  EXPECT_NEAR(a.radiance() + b.radiance(), 1.0, 2.5 * ci);
  EXPECT_GT(b.scattered.mean, 0.05);  // the ground's light does reach a ray looking up through the cloud
  EXPECT_LT(ci, 0.03);
}

// (d) Semi-infinite isotropic medium, single-scattering albedo 0.9: the reflected radiance is
// omega E mu0 H(mu) H(mu0) / (4 pi (mu + mu0)) exactly (Chandrasekhar 1960, "Radiative Transfer",
// ch. IV-V: diffuse reflection with the H function), H solved in the test by iteration.
TEST(CloudPathTracer, SemiInfiniteIsotropicMatchesChandrasekharH) {
  const double omega = 0.9;
  const testing::ChandrasekharH h(omega);
  const HomogeneousSlab deep(-60.0, 0.0, 1.0, omega);  // tau = 60: no light comes through.
  const HenyeyGreenstein isotropic(0.0);
  for (const auto& [view_zenith, sun_zenith] : {std::pair{0.0, 0.0}, std::pair{60.0, 30.0}}) {
    const double mu = std::cos(view_zenith * kPi / 180.0), mu0 = std::cos(sun_zenith * kPi / 180.0);
    const Lighting lighting{.sun_direction = direction_deg(sun_zenith, 0.0)};
    const Ray view{{0, 0, 10}, direction_deg(180.0 - view_zenith, 90.0)};
    const CloudRadianceEstimate r = path_trace(deep, isotropic, view, lighting, with_samples(40'000));
    const double expected = omega * mu0 * h(mu) * h(mu0) / (4.0 * kPi * (mu + mu0));
    EXPECT_NEAR(r.scattered.mean, expected, 2.5 * r.scattered.ci95) << view_zenith;
    EXPECT_LT(r.scattered.ci95, 0.02 * expected);
    EXPECT_EQ(r.truncated_paths, 0u);
  }
}

// (e) Stiff cases: extinction x0, x1000, g = +-0.999, a horizontal ray inside the slab.
TEST(CloudPathTracer, StiffCases) {
  const HenyeyGreenstein phase(0.8);
  const Lighting lighting{.sun_direction = direction_deg(30.0, 0.0), .sky_radiance = 0.25, .ground_radiance = 0.25};
  const Ray down{{0, 0, 600}, direction_deg(150.0, 0.0)};
  // x0: the background, exactly.
  const CloudRadianceEstimate empty = path_trace(HomogeneousSlab(0.0, 500.0, 0.0), phase, down, lighting, with_samples(1000));
  EXPECT_EQ(empty.scattered.mean, 0.0);
  EXPECT_EQ(empty.transmittance.mean, 1.0);
  EXPECT_EQ(empty.radiance(), 0.25);
  // x1000 (tau = 5000, conservative): finite, non-negative, the work bounded.
  PathTraceSettings bounded = with_samples(2000);
  bounded.max_steps_per_path = 100'000;
  const CloudRadianceEstimate dense = path_trace(HomogeneousSlab(0.0, 500.0, 10.0), phase, down, lighting, bounded);
  EXPECT_TRUE(std::isfinite(dense.radiance()));
  EXPECT_GT(dense.scattered.mean, 0.0);
  EXPECT_EQ(dense.transmittance.mean, 0.0);
  EXPECT_LT(dense.wall_ms, 20'000.0);
  EXPECT_LT(dense.truncated_paths, bounded.samples / 10);
  // Horizontal inside the slab: an infinite stretch; never escapes, so no background.
  const CloudRadianceEstimate horizontal =
      path_trace(HomogeneousSlab(0.0, 500.0, 0.01), phase, {{0, 0, 250}, {1, 0, 0}}, lighting, with_samples(2000));
  EXPECT_EQ(horizontal.transmittance.mean, 0.0);
  EXPECT_GT(horizontal.scattered.mean, 0.0);
  // g = +-0.999: finite and, at one order, still the quadrature's value.
  for (const double g : {0.999, -0.999}) {
    const HenyeyGreenstein sharp(g);
    const HomogeneousSlab slab(0.0, 500.0, 0.002);
    const Ray view{{0, 0, -10}, g > 0 ? direction_deg(35.0, 0.0) : direction_deg(145.0, 180.0)};  // 5 degrees off the peak.
    const Lighting sun{.sun_direction = direction_deg(30.0, 0.0)};
    const CloudRadianceEstimate first = path_trace(slab, sharp, g > 0 ? view : Ray{{0, 0, 510}, view.direction}, sun,
                                                   with_samples(20'000, 1));
    const double ss = single_scattering(slab, sharp, g > 0 ? view : Ray{{0, 0, 510}, view.direction}, sun).radiance;
    EXPECT_NEAR(first.scattered.mean, ss, 2.5 * first.scattered.ci95) << g;
    const CloudRadianceEstimate all = path_trace(slab, sharp, view, sun, with_samples(5000));
    EXPECT_TRUE(std::isfinite(all.scattered.mean) && all.scattered.mean >= 0.0) << g;
  }
}

// Same seed and samples: bitwise the same result whatever the thread count; another seed differs.
TEST(CloudPathTracer, DeterministicAcrossThreadCounts) {
  const HomogeneousSphere cloud({0, 0, 0}, 150.0, 0.02);
  const DualLobeHenyeyGreenstein phase;
  const Lighting lighting{.sun_direction = direction_deg(60.0, 20.0), .sky_radiance = 0.1, .ground_radiance = 0.1};
  const Ray view{{0, 0, -400}, {0, 0, 1}};
  PathTraceSettings s = with_samples(3000);
  s.threads = 1;
  const CloudRadianceEstimate one = path_trace(cloud, phase, view, lighting, s);
  s.threads = 3;
  const CloudRadianceEstimate three = path_trace(cloud, phase, view, lighting, s);
  EXPECT_EQ(one.scattered.mean, three.scattered.mean);
  EXPECT_EQ(one.scattered.ci95, three.scattered.ci95);
  EXPECT_EQ(one.transmittance.mean, three.transmittance.mean);
  s.seed = 2;
  EXPECT_NE(path_trace(cloud, phase, view, lighting, s).scattered.mean, one.scattered.mean);
}

// (f) The CI half-width at 4N samples is about half that at N.
TEST(CloudPathTracer, ErrorShrinksAsSamplesGrow) {
  const HomogeneousSphere cloud({0, 0, 0}, 150.0, 0.01);
  const HenyeyGreenstein phase(0.6);
  const Lighting lighting{.sun_direction = direction_deg(50.0, 0.0)};
  const Ray view{{0, 0, -400}, {0, 0, 1}};
  const double n = path_trace(cloud, phase, view, lighting, with_samples(4000)).scattered.ci95;
  const double four_n = path_trace(cloud, phase, view, lighting, with_samples(16'000)).scattered.ci95;
  EXPECT_GT(four_n / n, 0.4);
  EXPECT_LT(four_n / n, 0.6);
}

}  // namespace
}  // namespace welkin::clouds::reference
