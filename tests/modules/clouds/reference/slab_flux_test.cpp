#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "reference/cloud_path_tracer.h"
#include "test_support.h"

namespace welkin::clouds::reference {
namespace {

using testing::direction_deg;

PathTraceSettings with_samples(std::uint64_t samples) {
  PathTraceSettings s;
  s.samples = samples;
  return s;
}

// (b) Energy conservation of a non-absorbing slab (tau = 1, HG 0.5, sun 40 degrees from the
// zenith): reflected + transmitted (direct + diffuse) = 1, the direct part is exp(-tau / mu0), and
// the reflected flux equals the hemispherical integral of the radiance path tracer's reflected
// radiance, int L mu dw / (E mu0) (Gauss-Legendre in mu, trapezoid in azimuth, folded by symmetry).
TEST(SlabFlux, ConservativeSlabConservesEnergyAndMatchesRadiance) {
  const double tau = 1.0, mu0 = std::cos(40.0 * kPi / 180.0);
  const HomogeneousSlab slab(0.0, 200.0, tau / 200.0);
  const HenyeyGreenstein phase(0.5);
  const glm::dvec3 sun = direction_deg(40.0, 0.0);
  const SlabFluxEstimate flux = slab_flux(slab, phase, 200.0, sun, with_samples(200'000));
  EXPECT_EQ(flux.truncated_paths, 0u);
  EXPECT_EQ(flux.absorbed.mean, 0.0);
  EXPECT_NEAR(flux.reflected.mean + flux.transmitted_direct.mean + flux.transmitted_diffuse.mean, 1.0, 1e-12);
  EXPECT_NEAR(flux.transmitted_direct.mean, std::exp(-tau / mu0), 2.5 * flux.transmitted_direct.ci95);

  const Lighting lighting{.sun_direction = sun};
  double reflected = 0.0, variance = 0.0;
  const int azimuths = 6;  // 0, 36, ..., 180 degrees; the radiance is even in azimuth.
  for (const auto& [mu, w_mu] : testing::gauss_legendre(6, 0.0, 1.0)) {
    for (int a = 0; a < azimuths; ++a) {
      const double phi = 180.0 * a / (azimuths - 1);
      const double w_phi = (a == 0 || a == azimuths - 1 ? 0.5 : 1.0) * 2.0 * kPi / (2.0 * (azimuths - 1));
      const Ray view{{0, 0, 300}, direction_deg(180.0 - std::acos(mu) * 180.0 / kPi, phi)};
      const CloudRadianceEstimate r = path_trace(slab, phase, view, lighting, with_samples(8000));
      const double w = 2.0 * w_phi * w_mu * mu / mu0;  // x 2: azimuths (180, 360) by symmetry.
      reflected += w * r.scattered.mean;
      variance += w * w * (r.scattered.ci95 / 1.96) * (r.scattered.ci95 / 1.96);
    }
  }
  const double ci = 1.96 * std::sqrt(variance + std::pow(flux.reflected.ci95 / 1.96, 2));
  EXPECT_NEAR(reflected, flux.reflected.mean, 2.5 * ci + 0.01 * flux.reflected.mean);
}

// With absorption, reflected + transmitted + absorbed = 1 within the estimates' error.
TEST(SlabFlux, AbsorbingSlabBalances) {
  const HomogeneousSlab slab(0.0, 100.0, 0.03, 0.8);
  const SlabFluxEstimate flux = slab_flux(slab, DualLobeHenyeyGreenstein(), 100.0, direction_deg(20.0, 0.0),
                                          with_samples(100'000));
  const double total = flux.reflected.mean + flux.transmitted_direct.mean + flux.transmitted_diffuse.mean +
                       flux.absorbed.mean;
  const double ci = std::hypot(std::hypot(flux.reflected.ci95, flux.transmitted_diffuse.ci95),
                               std::hypot(flux.transmitted_direct.ci95, flux.absorbed.ci95));
  EXPECT_NEAR(total, 1.0, 2.5 * ci);
  EXPECT_GT(flux.absorbed.mean, 0.1);
}

// (d) Semi-infinite isotropic medium: the plane albedo is 1 - H(mu0) sqrt(1 - omega) (Chandrasekhar
// 1960, "Radiative Transfer"), here at omega = 0.9 for two sun heights. The test's H solver is
// checked against Chandrasekhar's table for conservative isotropic scattering (H(0.5) = 2.01278,
// H(1) = 2.90781).
TEST(SlabFlux, SemiInfinitePlaneAlbedoMatchesChandrasekhar) {
  const testing::ChandrasekharH conservative(1.0);
  EXPECT_NEAR(conservative(1.0), 2.90781, 5e-5);
  EXPECT_NEAR(conservative(0.5), 2.01278, 5e-5);
  const double omega = 0.9;
  const testing::ChandrasekharH h(omega);
  const HomogeneousSlab deep(-60.0, 0.0, 1.0, omega);
  for (const double zenith : {0.0, 60.0}) {
    const double mu0 = std::cos(zenith * kPi / 180.0);
    const SlabFluxEstimate flux = slab_flux(deep, HenyeyGreenstein(0.0), 0.0, direction_deg(zenith, 0.0),
                                            with_samples(100'000));
    const double expected = 1.0 - h(mu0) * std::sqrt(1.0 - omega);
    EXPECT_NEAR(flux.reflected.mean, expected, 2.5 * flux.reflected.ci95) << zenith;
    EXPECT_LT(flux.reflected.ci95, 0.01);
    EXPECT_LT(flux.transmitted_diffuse.mean, 1e-6);
  }
}

}  // namespace
}  // namespace welkin::clouds::reference
