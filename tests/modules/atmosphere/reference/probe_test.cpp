#include "reference/probe.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

using testing::constant_shell;
using testing::naive_visible_length;

constexpr double kR = 6360.0;

TEST(Probe, LocalFrameHasZUpAndAzimuthFromXTowardsY) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const ProbeRay ray = probe_ray(m, {.altitude_km = 2.0,
                                     .view_zenith_deg = 90.0,
                                     .view_azimuth_deg = 90.0,
                                     .sun_zenith_deg = 0.0});
  EXPECT_EQ(ray.camera_km, glm::dvec3(0.0, 0.0, kR + 2.0));
  EXPECT_NEAR(ray.view_dir.x, 0.0, 1e-15);
  EXPECT_NEAR(ray.view_dir.y, 1.0, 1e-15);
  EXPECT_NEAR(ray.view_dir.z, 0.0, 1e-15);
  EXPECT_EQ(ray.sun_dir, glm::dvec3(0.0, 0.0, 1.0));
  // Under the ground: clamped to it.
  EXPECT_EQ(probe_ray(m, {.altitude_km = -3.0}).camera_km, glm::dvec3(0.0, 0.0, kR));
}

TEST(Probe, TransmittanceIsExpOfSigmaTimesChordInAConstantShell) {
  const glm::dvec3 sigma(0.01, 0.02, 0.04);
  const AtmosphereModel m = constant_shell(sigma, kR, kR + 100.0);
  for (double zenith : {0.0, 45.0, 89.0, 90.0, 100.0}) {
    const ProbeResult p = probe_quadrature(m, {.altitude_km = 5.0, .view_zenith_deg = zenith});
    const double length =
        naive_visible_length(kR + 5.0, std::cos(zenith * kPi / 180.0), kR, kR + 100.0);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(p.transmittance[c], std::exp(-sigma[c] * length), 1e-9) << zenith;
    }
  }
}

// Only the relative azimuth of view and sun matters, and its sign does not (mirror symmetry).
TEST(Probe, DependsOnlyOnRelativeAzimuth) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const ProbeGeometry base{.altitude_km = 1.0,
                           .view_zenith_deg = 80.0,
                           .view_azimuth_deg = 10.0,
                           .sun_zenith_deg = 70.0,
                           .sun_azimuth_deg = 50.0};
  ProbeGeometry rotated = base;
  rotated.view_azimuth_deg += 133.0;
  rotated.sun_azimuth_deg += 133.0;
  ProbeGeometry mirrored = base;
  mirrored.sun_azimuth_deg = -30.0;  // 40 degrees on the other side of the view.
  const ProbeResult a = probe_quadrature(m, base);
  const ProbeResult b = probe_quadrature(m, rotated);
  const ProbeResult c = probe_quadrature(m, mirrored);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(b.radiance[ch], a.radiance[ch], 1e-9 * a.radiance[ch]);
    EXPECT_NEAR(c.radiance[ch], a.radiance[ch], 1e-9 * a.radiance[ch]);
    EXPECT_LT(a.radiance_ci95[ch], 1e-6 * a.radiance[ch]);
  }
  ProbeGeometry towards_sun = base;
  towards_sun.sun_azimuth_deg = base.view_azimuth_deg;
  EXPECT_GT(probe_quadrature(m, towards_sun).radiance[0], 1.5 * a.radiance[0]);  // Mie peak.
}

TEST(Probe, PathTracedFirstOrderMatchesQuadrature) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const ProbeGeometry g{.altitude_km = 0.5,
                        .view_zenith_deg = 85.0,
                        .view_azimuth_deg = 0.0,
                        .sun_zenith_deg = 80.0,
                        .sun_azimuth_deg = 90.0};
  PathTraceSettings s;
  s.samples = 100'000;
  s.max_order = 1;
  const ProbeResult q = probe_quadrature(m, g);
  const ProbeResult p = probe_path_traced(m, g, s);
  EXPECT_EQ(q.samples, 0u);
  EXPECT_EQ(p.samples, 100'000u);
  EXPECT_GT(p.wall_ms, 0.0);
  EXPECT_GT(q.wall_ms, 0.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(p.transmittance[c], q.transmittance[c]);
    EXPECT_NEAR(p.radiance[c], q.radiance[c], 2.5 * p.radiance_ci95[c]);
    EXPECT_LT(p.radiance_ci95[c], 0.05 * q.radiance[c]);
  }
}

}  // namespace
}  // namespace welkin::atmosphere::reference
