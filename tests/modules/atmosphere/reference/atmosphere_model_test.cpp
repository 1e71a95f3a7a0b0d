#include "reference/atmosphere_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

using testing::integrate_mu_graded;

bool mentions(const std::vector<std::string>& problems, const std::string& needle) {
  return std::any_of(problems.begin(), problems.end(),
                     [&](const std::string& p) { return p.find(needle) != std::string::npos; });
}

TEST(DensityProfile, FollowsBrunetonLayerSemantics) {
  DensityProfile p;
  p.layers[0] = {.width_km = 10.0, .constant_term = 0.25};
  p.layers[1] = {
      .exp_term = 2.0, .exp_scale_per_km = -0.1, .linear_term_per_km = -0.01, .constant_term = 0.1};
  EXPECT_DOUBLE_EQ(p.density(0.0), 0.25);
  EXPECT_DOUBLE_EQ(p.density(9.999), 0.25);
  // Layer 1 from its boundary on: 2 e^-1 - 0.1 + 0.1.
  EXPECT_DOUBLE_EQ(p.density(10.0), 2.0 * std::exp(-1.0));
  EXPECT_DOUBLE_EQ(p.density(20.0), 2.0 * std::exp(-2.0) - 0.2 + 0.1);
  // Clamped to [0, 1] on both sides.
  DensityProfile clamp;
  clamp.layers[1] = {.linear_term_per_km = 0.5, .constant_term = -1.0};
  EXPECT_EQ(clamp.density(0.0), 0.0);
  EXPECT_DOUBLE_EQ(clamp.density(3.0), 0.5);
  EXPECT_EQ(clamp.density(10.0), 1.0);
}

TEST(AtmosphereModel, EarthMatchesHillaire2020Constants) {
  const AtmosphereModel m = AtmosphereModel::earth();
  EXPECT_TRUE(m.validate().empty());
  EXPECT_EQ(m.bottom_radius_km, 6360.0);
  EXPECT_EQ(m.top_radius_km, 6460.0);
  // Hillaire 2020 table: Rayleigh (5.802, 13.558, 33.1) 1/Mm, H = 8 km.
  EXPECT_DOUBLE_EQ(m.coefficients(0.0).rayleigh_scattering.z, 33.1e-3);
  EXPECT_NEAR(m.coefficients(8.0).rayleigh_scattering.x / 5.802e-3, std::exp(-1.0), 1e-15);
  // Mie 3.996 / 4.440 1/Mm, H = 1.2 km.
  EXPECT_NEAR(m.coefficients(1.2).mie_scattering.y / 3.996e-3, std::exp(-1.0), 1e-15);
  // Ozone tent: 0 below 10 km, peak 1 at 25 km, 0.5 at 17.5 and 32.5 km, 0 above 40 km.
  EXPECT_EQ(m.absorption_density.density(5.0), 0.0);
  EXPECT_NEAR(m.absorption_density.density(17.5), 0.5, 1e-15);
  EXPECT_NEAR(m.absorption_density.density(25.0), 1.0, 1e-15);
  EXPECT_NEAR(m.absorption_density.density(32.5), 0.5, 1e-15);
  EXPECT_EQ(m.absorption_density.density(45.0), 0.0);
  // Extinction at 25 km: Rayleigh + Mie extinction + ozone, written out by hand.
  const double h = 25.0;
  const double expected_green =
      13.558e-3 * std::exp(-h / 8.0) + 4.440e-3 * std::exp(-h / 1.2) + 1.881e-3;
  EXPECT_NEAR(m.extinction(h).y, expected_green, 1e-15);
  EXPECT_EQ(m.extinction(-0.1), glm::dvec3(0.0));   // Under the ground.
  EXPECT_EQ(m.extinction(100.1), glm::dvec3(0.0));  // Above the top.
  EXPECT_NEAR(m.max_extinction(), 33.1e-3 + 4.440e-3 + 0.085e-3, 1e-15);
}

TEST(AtmosphereModel, KinkAltitudesOfTheOzoneTent) {
  const std::vector<double> kinks = AtmosphereModel::earth().kink_altitudes_km();
  ASSERT_EQ(kinks.size(), 3u);
  EXPECT_NEAR(kinks[0], 10.0, 1e-12);
  EXPECT_NEAR(kinks[1], 25.0, 1e-12);
  EXPECT_NEAR(kinks[2], 40.0, 1e-12);
}

TEST(AtmosphereModel, ValidateListsEveryProblem) {
  AtmosphereModel m = AtmosphereModel::earth();
  m.top_radius_km = m.bottom_radius_km;
  m.rayleigh_scattering.y = -1e-3;
  m.mie_scattering.x = std::numeric_limits<double>::quiet_NaN();
  m.mie_extinction.z = 1e-3;  // Below mie_scattering.z.
  m.absorption_extinction.x = std::numeric_limits<double>::infinity();
  m.mie_g = 1.0;
  m.ground_albedo.z = 1.5;
  m.mie_density.layers[1].exp_scale_per_km = std::numeric_limits<double>::quiet_NaN();
  m.absorption_density.layers[0].width_km = -3.0;
  const std::vector<std::string> problems = m.validate();
  EXPECT_EQ(problems.size(), 9u);
  EXPECT_TRUE(mentions(problems, "top_radius_km"));
  EXPECT_TRUE(mentions(problems, "rayleigh_scattering.g is negative"));
  EXPECT_TRUE(mentions(problems, "mie_scattering.r is not finite"));
  EXPECT_TRUE(mentions(problems, "mie_extinction.b"));
  EXPECT_TRUE(mentions(problems, "absorption_extinction.r is not finite"));
  EXPECT_TRUE(mentions(problems, "mie_g"));
  EXPECT_TRUE(mentions(problems, "ground_albedo.b"));
  EXPECT_TRUE(mentions(problems, "mie_density.layers[1].exp_scale_per_km"));
  EXPECT_TRUE(mentions(problems, "absorption_density.layers[0].width_km is negative"));

  AtmosphereModel g_low = AtmosphereModel::earth();
  g_low.mie_g = -1.0;
  EXPECT_EQ(g_low.validate().size(), 1u);
  AtmosphereModel radius = AtmosphereModel::earth();
  radius.bottom_radius_km = 0.0;
  EXPECT_TRUE(mentions(radius.validate(), "bottom_radius_km"));
}

TEST(AtmosphereModel, ScalingHelpers) {
  const AtmosphereModel earth = AtmosphereModel::earth();
  const AtmosphereModel big = earth.scaled(10.0);
  EXPECT_DOUBLE_EQ(big.bottom_radius_km, 63600.0);
  // Same density at the same fraction of the thickness; coefficients divided by 10.
  EXPECT_NEAR(big.extinction(250.0).y * 10.0, earth.extinction(25.0).y, 1e-17);
  EXPECT_TRUE(big.validate().empty());
  const AtmosphereModel thick = earth.with_density_scale(1000.0);
  EXPECT_NEAR(thick.extinction(3.0).z, 1000.0 * earth.extinction(3.0).z, 1e-12);
}

TEST(PhaseFunctions, KnownValues) {
  EXPECT_DOUBLE_EQ(rayleigh_phase(0.0), 3.0 / (16.0 * kPi));
  EXPECT_DOUBLE_EQ(rayleigh_phase(-1.0), 3.0 / (8.0 * kPi));
  EXPECT_DOUBLE_EQ(henyey_greenstein_phase(0.0, 0.3), 1.0 / (4.0 * kPi));
  // Cornette-Shanks reduces to Rayleigh at g = 0.
  for (double mu : {-1.0, -0.3, 0.0, 0.7, 1.0}) {
    EXPECT_NEAR(cornette_shanks_phase(0.0, mu), rayleigh_phase(mu), 1e-16);
  }
  // HG forward peak (1 + g) / (4 pi (1 - g)^2): stays exact at g = 0.999.
  EXPECT_NEAR(henyey_greenstein_phase(0.999, 1.0) / (1.999 / (4.0 * kPi * 1e-6)), 1.0, 1e-9);
  EXPECT_NEAR(henyey_greenstein_phase(-0.999, -1.0) / (1.999 / (4.0 * kPi * 1e-6)), 1.0, 1e-9);
}

// Integral over the sphere of p and of mu p (mean cosine), by an independent graded
// Gauss-Legendre rule. Mean cosines: HG g; CS 3 g (4 + g^2) / (5 (2 + g^2)); Rayleigh 0.
TEST(PhaseFunctions, NormalisedAndMeanCosineIncludingExtremeAnisotropy) {
  auto sphere = [](auto p) { return 2.0 * kPi * integrate_mu_graded(p); };
  EXPECT_NEAR(sphere([](double mu) { return rayleigh_phase(mu); }), 1.0, 1e-12);
  EXPECT_NEAR(sphere([](double mu) { return mu * rayleigh_phase(mu); }), 0.0, 1e-14);
  for (double g : {-0.999, -0.9, -0.5, 0.0, 0.3, 0.8, 0.99, 0.999}) {
    SCOPED_TRACE(g);
    EXPECT_NEAR(sphere([g](double mu) { return henyey_greenstein_phase(g, mu); }), 1.0, 1e-9);
    EXPECT_NEAR(sphere([g](double mu) { return cornette_shanks_phase(g, mu); }), 1.0, 1e-9);
    EXPECT_NEAR(sphere([g](double mu) { return mu * henyey_greenstein_phase(g, mu); }), g, 1e-9);
    EXPECT_NEAR(sphere([g](double mu) { return mu * cornette_shanks_phase(g, mu); }),
                3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g)), 1e-9);
  }
  AtmosphereModel hg = AtmosphereModel::earth();
  hg.mie_phase = MiePhase::henyey_greenstein;
  EXPECT_DOUBLE_EQ(hg.mie_phase_value(0.5), henyey_greenstein_phase(0.8, 0.5));
  EXPECT_DOUBLE_EQ(AtmosphereModel::earth().mie_phase_value(0.5), cornette_shanks_phase(0.8, 0.5));
}

}  // namespace
}  // namespace welkin::atmosphere::reference
