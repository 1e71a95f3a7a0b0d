#include "reference/single_scattering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "reference/transmittance.h"
#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

using testing::constant_shell;
using testing::naive_visible_length;

constexpr double kR = 6360.0;
constexpr double kTop = 6460.0;

glm::dvec3 dir(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * kPi / 180.0, a = azimuth_deg * kPi / 180.0;
  return {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
}

void expect_rel(const glm::dvec3& actual, const glm::dvec3& expected, double rel) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(actual[c], expected[c], rel * std::abs(expected[c])) << "channel " << c;
  }
}

// Constant-density shell with both Rayleigh and Mie scattering and some Mie absorption.
AtmosphereModel constant_mixed_shell(double scale) {
  AtmosphereModel m = constant_shell(glm::dvec3(0.004, 0.01, 0.03) * scale, kR, kTop);
  m.mie_scattering = glm::dvec3(0.003) * scale;
  m.mie_extinction = glm::dvec3(0.004) * scale;
  m.mie_density.layers[1] = {.constant_term = 1.0};
  return m;
}

// View and sun both at the zenith: T(camera -> x) T_sun(x) = exp(-sigma_t l) for every x, so
// L = sigma_s p(1) l exp(-sigma_t l) exactly, however thick the medium.
TEST(SingleScattering, ZenithSunZenithViewClosedForm) {
  for (double scale : {1e-3, 1.0, 30.0}) {
    const AtmosphereModel m = constant_mixed_shell(scale);
    for (double h0 : {0.0, 40.0}) {
      const double l = 100.0 - h0;
      const LocalCoefficients k = m.coefficients(1.0);
      const glm::dvec3 expected = (k.rayleigh_scattering * rayleigh_phase(1.0) +
                                   k.mie_scattering * m.mie_phase_value(1.0)) *
                                  l * glm::exp(-k.extinction * l);
      const SingleScatteringResult ss =
          single_scattering(m, glm::dvec3(0, 0, kR + h0), dir(0, 0), dir(0, 0));
      SCOPED_TRACE(::testing::Message() << scale << " " << h0);
      EXPECT_TRUE(ss.converged);
      expect_rel(ss.radiance, expected, 1e-7);
      expect_rel(ss.transmittance, glm::exp(-k.extinction * l), 1e-9);
    }
  }
}

// Optically thin: L -> sigma_s p(nu) * visible length, for any lit geometry.
TEST(SingleScattering, OpticallyThinMatchesSigmaTimesPhaseTimesLength) {
  const AtmosphereModel m = constant_mixed_shell(1e-9);
  struct Case {
    double altitude, view_zenith, view_azimuth, sun_zenith, sun_azimuth;
  };
  for (const Case c : std::vector<Case>{{0, 0, 0, 30, 0},
                                        {0, 60, 0, 30, 0},
                                        {0, 84, 90, 30, 200},
                                        {0, 89.9, 0, 50, 0},
                                        {50, 95, 0, 10, 0},  // Looking down to the ground.
                                        {50, 120, 0, 10, 0},
                                        {5, 10, 0, 10, 0}}) {  // Near the Mie forward peak.
    const glm::dvec3 view = dir(c.view_zenith, c.view_azimuth);
    const glm::dvec3 sun = dir(c.sun_zenith, c.sun_azimuth);
    const double r = kR + c.altitude;
    const double l = naive_visible_length(r, view.z, kR, kTop);
    const double nu = glm::dot(view, sun);
    const LocalCoefficients k = m.coefficients(1.0);
    const glm::dvec3 expected =
        (k.rayleigh_scattering * rayleigh_phase(nu) + k.mie_scattering * m.mie_phase_value(nu)) * l;
    SCOPED_TRACE(::testing::Message() << c.altitude << " " << c.view_zenith << " " << c.sun_zenith);
    expect_rel(single_scattering(m, glm::dvec3(0, 0, r), view, sun).radiance, expected, 1e-5);
    // And a short segment: sigma_s p d.
    SingleScatteringSettings short_segment;
    short_segment.max_distance_km = 0.5;
    expect_rel(single_scattering(m, glm::dvec3(0, 0, r), view, sun, short_segment).radiance,
               expected * (0.5 / l), 1e-5);
  }
}

// Optically thick: seen from its top, a semi-infinite homogeneous medium reflects by single
// scattering L = (sigma_s / sigma_t) p(nu) mu_s / (mu_s + m), m the cosine of the downward view
// (a classic plane-parallel result). Mean free paths of 0.3 to 1.3 m here, so the curvature is
// negligible; and all the light comes from a layer far thinner than the 115 km view ray.
TEST(SingleScattering, OpticallyThickSlabMatchesPlaneParallelReflection) {
  const AtmosphereModel m = constant_mixed_shell(1e5);  // sigma_t from 800 to 3400 per km.
  const LocalCoefficients k = m.coefficients(1.0);
  for (double view_zenith : {150.0, 120.0, 100.0}) {
    for (double sun_zenith : {0.0, 40.0, 80.0}) {
      const glm::dvec3 view = dir(view_zenith, 0.0), sun = dir(sun_zenith, 60.0);
      const double nu = glm::dot(view, sun), m_cos = -view.z;
      const glm::dvec3 expected =
          (k.rayleigh_scattering * rayleigh_phase(nu) + k.mie_scattering * m.mie_phase_value(nu)) /
          k.extinction * (sun.z / (sun.z + m_cos));
      SCOPED_TRACE(::testing::Message() << view_zenith << " " << sun_zenith);
      // 3e-6: curvature over the few metres the light travels sideways at grazing angles.
      expect_rel(single_scattering(m, glm::dvec3(0, 0, kTop), view, sun).radiance, expected, 3e-6);
    }
  }
}

// Independent brute force: midpoint sums along the view ray (cumulative optical depth) and along
// each sun ray (naive geometry), at two resolutions combined by Richardson extrapolation.
glm::dvec3 brute_force(const AtmosphereModel& m, const glm::dvec3& camera, const glm::dvec3& view,
                       const glm::dvec3& sun, int n_view, int n_sun) {
  const double r = glm::length(camera);
  const double length = naive_visible_length(r, glm::dot(camera, view) / r, kR, kTop);
  const double h = length / n_view;
  auto altitude = [](const glm::dvec3& p) { return glm::length(p) - kR; };
  glm::dvec3 tau_view(0.0), sum(0.0);
  for (int i = 0; i < n_view; ++i) {
    const glm::dvec3 x = camera + (i + 0.5) * h * view;
    const glm::dvec3 tau_to_x =
        tau_view + m.extinction(altitude(camera + (i + 0.25) * h * view)) * h * 0.5;
    tau_view += m.extinction(altitude(x)) * h;
    const double rx = glm::length(x);
    const double mu_s = glm::dot(x, sun) / rx;
    const double below = rx * rx * (1.0 - mu_s * mu_s) - kR * kR;
    if (mu_s < 0.0 && below < 0.0) continue;  // Planet shadow.
    const double sun_length = naive_visible_length(rx, mu_s, kR, kTop);
    const double hs = sun_length / n_sun;
    glm::dvec3 tau_sun(0.0);
    for (int j = 0; j < n_sun; ++j)
      tau_sun += m.extinction(altitude(x + (j + 0.5) * hs * sun)) * hs;
    const LocalCoefficients k = m.coefficients(altitude(x));
    const double nu = glm::dot(view, sun);
    sum += glm::exp(-tau_to_x - tau_sun) *
           (k.rayleigh_scattering * rayleigh_phase(nu) + k.mie_scattering * m.mie_phase_value(nu)) *
           h;
  }
  return sum;
}

TEST(SingleScattering, EarthMatchesNestedBruteForceSum) {
  const AtmosphereModel m = AtmosphereModel::earth();
  struct Case {
    double altitude, view_zenith, sun_zenith, sun_azimuth;
  };
  for (const Case c : std::vector<Case>{{0.0, 60.0, 45.0, 90.0}, {20.0, 90.0, 80.0, 180.0}}) {
    const glm::dvec3 camera(0, 0, kR + c.altitude), view = dir(c.view_zenith, 0);
    const glm::dvec3 sun = dir(c.sun_zenith, c.sun_azimuth);
    const glm::dvec3 coarse = brute_force(m, camera, view, sun, 1000, 1000);
    const glm::dvec3 fine = brute_force(m, camera, view, sun, 2000, 2000);
    const glm::dvec3 extrapolated = (4.0 * fine - coarse) / 3.0;
    SCOPED_TRACE(c.view_zenith);
    expect_rel(single_scattering(m, camera, view, sun).radiance, extrapolated, 3e-6);
  }
}

// Sun below the horizon: the planet's shadow covers the start of the ray. A first-order brute
// force (the shadow edge is a jump) at a fine step.
TEST(SingleScattering, PlanetShadowMatchesBruteForce) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 camera(0, 0, kR), view = dir(80.0, 0.0), sun = dir(95.0, 0.0);
  const glm::dvec3 brute = brute_force(m, camera, view, sun, 8000, 1000);
  const SingleScatteringResult ss = single_scattering(m, camera, view, sun);
  expect_rel(ss.radiance, brute, 2e-3);
  // Without the shadow the answer would be far larger.
  const SingleScatteringResult lit = single_scattering(m, camera, view, dir(89.0, 0.0));
  EXPECT_GT(lit.radiance.x, 3.0 * ss.radiance.x);
}

TEST(SingleScattering, DarkWhenTheWholeRayIsInShadow) {
  const AtmosphereModel m = AtmosphereModel::earth();
  for (double sun_zenith : {120.0, 180.0}) {
    const SingleScatteringResult ss =
        single_scattering(m, glm::dvec3(0, 0, kR), dir(0, 0), dir(sun_zenith, 0));
    EXPECT_EQ(ss.radiance, glm::dvec3(0.0));
  }
}

TEST(SingleScattering, ScaleInvariantOnTinyAndHugePlanets) {
  const AtmosphereModel earth = AtmosphereModel::earth();
  for (double bottom : {1.0, 100000.0}) {
    const double k = bottom / kR;
    const AtmosphereModel m = earth.scaled(k);
    for (double sun_zenith : {30.0, 92.0}) {
      const glm::dvec3 camera(0, 0, kR + 2.0), view = dir(85.0, 0), sun = dir(sun_zenith, 30);
      SCOPED_TRACE(::testing::Message() << bottom << " " << sun_zenith);
      expect_rel(single_scattering(m, camera * k, view, sun).radiance,
                 single_scattering(earth, camera, view, sun).radiance, 2e-6);
    }
  }
}

TEST(SingleScattering, BrunetonParametrisationMatchesVectors) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 view = dir(70.0, 0.0), sun = dir(50.0, 120.0);
  const double r = kR + 3.0;
  expect_rel(single_scattering(m, r, view.z, sun.z, glm::dot(view, sun)).radiance,
             single_scattering(m, glm::dvec3(0, 0, r), view, sun).radiance, 1e-9);
}

TEST(SingleScattering, GrowsWithDistanceAndReportsViewTransmittance) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 camera(0, 0, kR + 1.0), view = dir(88.0, 0), sun = dir(60.0, 45.0);
  glm::dvec3 previous(0.0);
  for (double d : {1.0, 10.0, 100.0, 1000.0}) {
    SingleScatteringSettings s;
    s.max_distance_km = d;
    const SingleScatteringResult ss = single_scattering(m, camera, view, sun, s);
    for (int c = 0; c < 3; ++c) EXPECT_GT(ss.radiance[c], previous[c]);
    expect_rel(ss.transmittance, transmittance_between(m, kR + 1.0, view.z, d), 1e-9);
    previous = ss.radiance;
  }
}

// Stiff cases from DESIGN.md: finite, non-negative, transmittance in [0, 1].
TEST(SingleScattering, StiffAndExtremeCasesStayFiniteAndNonNegative) {
  const AtmosphereModel earth = AtmosphereModel::earth();
  std::vector<AtmosphereModel> models = {earth, earth.with_density_scale(0.0),
                                         earth.with_density_scale(1000.0), earth.scaled(1.0 / kR),
                                         earth.scaled(100000.0 / kR)};
  for (double g : {0.999, -0.999}) {
    for (MiePhase phase : {MiePhase::cornette_shanks, MiePhase::henyey_greenstein}) {
      AtmosphereModel m = earth;
      m.mie_g = g;
      m.mie_phase = phase;
      models.push_back(m);
    }
  }
  AtmosphereModel tiny = earth;  // Earth's 100 km atmosphere around a 1 km planet.
  tiny.bottom_radius_km = 1.0;
  tiny.top_radius_km = 101.0;
  models.push_back(tiny);
  for (const AtmosphereModel& m : models) {
    const double R = m.bottom_radius_km, H = m.thickness_km();
    const double grazing = -std::sqrt(1.0 - (R / (R + 0.5 * H)) * (R / (R + 0.5 * H)));
    struct Camera {
      double r, view_zenith_cos;
    };
    const std::vector<Camera> cameras = {{R, 1.0},
                                         {R, 0.0},
                                         {R - 0.5 * std::min(0.1 * H, R), 0.2},
                                         {R + H, -0.3},
                                         {R + H, 0.0},
                                         {R + 3.0 * H, -0.9},
                                         {R + 0.5 * H, grazing},
                                         {R + 0.5 * H, grazing + 1e-7},
                                         {R + 0.5 * H, grazing - 1e-7}};
    for (const Camera& c : cameras) {
      const glm::dvec3 view(std::sqrt(1.0 - c.view_zenith_cos * c.view_zenith_cos), 0.0,
                            c.view_zenith_cos);
      for (double sun_zenith : {0.0, 89.0, 90.0, 90.5, 100.0, 180.0}) {
        for (double sun_azimuth : {0.0, 180.0}) {
          const SingleScatteringResult ss =
              single_scattering(m, glm::dvec3(0, 0, c.r), view, dir(sun_zenith, sun_azimuth));
          for (int ch = 0; ch < 3; ++ch) {
            ASSERT_TRUE(std::isfinite(ss.radiance[ch]) && ss.radiance[ch] >= 0.0)
                << m.bottom_radius_km << " r=" << c.r << " mu=" << c.view_zenith_cos
                << " sun=" << sun_zenith;
            ASSERT_TRUE(ss.transmittance[ch] >= 0.0 && ss.transmittance[ch] <= 1.0);
          }
        }
      }
    }
  }
}

// Looser outer tolerances give larger, but honestly bounded, errors. Looking down from the top
// into a 100 m scale-height haze: nearly all the light comes from the last few hundred metres.
TEST(SingleScattering, ErrorShrinksAsToleranceTightens) {
  AtmosphereModel m = constant_shell(glm::dvec3(0.01, 0.02, 0.04), kR, kTop);
  m.rayleigh_density.layers[1] = {.exp_term = 1.0, .exp_scale_per_km = -1.0 / 0.1};
  const glm::dvec3 camera(0, 0, kTop), view = dir(120.0, 0), sun = dir(30.0, 10.0);
  SingleScatteringSettings tight;
  tight.outer.relative_tolerance = 1e-12;
  tight.inner.relative_tolerance = 1e-12;
  const glm::dvec3 exact = single_scattering(m, camera, view, sun, tight).radiance;
  std::vector<double> errors;
  int previous_evaluations = 0;
  for (double tol : {1e-1, 1e-3, 1e-7, 1e-9}) {
    SingleScatteringSettings s;
    s.outer.relative_tolerance = tol;
    const SingleScatteringResult q = single_scattering(m, camera, view, sun, s);
    const double error = glm::length(q.radiance - exact) / glm::length(exact);
    SCOPED_TRACE(tol);
    EXPECT_LE(error, tol);
    if (!errors.empty()) {
      EXPECT_LE(error, errors.back() + 1e-12);  // Inner-tolerance floor.
    }
    EXPECT_GE(q.evaluations, previous_evaluations);
    errors.push_back(error);
    previous_evaluations = q.evaluations;
  }
  EXPECT_LT(errors.back(), 0.01 * errors.front());
}

}  // namespace
}  // namespace welkin::atmosphere::reference
