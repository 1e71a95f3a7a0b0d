#include "reference/path_tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/exponential.hpp>
#include <vector>

#include "reference/single_scattering.h"
#include "reference/transmittance.h"
#include "test_support.h"

namespace welkin::atmosphere::reference {
namespace {

constexpr double kR = 6360.0;

glm::dvec3 dir(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * kPi / 180.0, a = azimuth_deg * kPi / 180.0;
  return {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
}

struct Geometry {
  double altitude, view_zenith, sun_zenith, sun_azimuth;
};

// max_order = 1 estimates exactly the single-scattering integral: agreement within 2.5 CI95
// half-widths (about 5 sigma) per channel, with a CI tight enough for the check to bite.
TEST(PathTracer, FirstOrderAgreesWithSingleScatteringQuadrature) {
  const AtmosphereModel m = AtmosphereModel::earth();
  for (const Geometry g : std::vector<Geometry>{{0.0, 0.0, 0.0, 0.0},
                                                {0.0, 70.0, 60.0, 150.0},
                                                {1.0, 89.0, 85.0, 0.0},
                                                {30.0, 95.0, 91.0, 0.0},
                                                {500.0, 111.5, 40.0, 0.0}}) {  // Limb from orbit.
    const glm::dvec3 camera(0, 0, kR + g.altitude), view = dir(g.view_zenith, 0);
    const glm::dvec3 sun = dir(g.sun_zenith, g.sun_azimuth);
    PathTraceSettings s;
    // Looking into the sun, the Mie forward peak makes rare collisions dominate: more paths.
    s.samples = g.view_zenith == g.sun_zenith ? 300'000 : 100'000;
    s.max_order = 1;
    const PathTraceResult pt = path_trace(m, camera, view, sun, s);
    const glm::dvec3 ss = single_scattering(m, camera, view, sun).radiance;
    SCOPED_TRACE(::testing::Message() << g.altitude << " " << g.view_zenith << " " << g.sun_zenith);
    EXPECT_EQ(pt.samples, s.samples);
    EXPECT_EQ(pt.truncated_paths, 0u);
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(pt.ci95[c], 0.06 * ss[c]);
      EXPECT_NEAR(pt.radiance[c], ss[c], 2.5 * pt.ci95[c]) << "channel " << c;
    }
  }
}

// Higher orders only add light: the all-orders estimate exceeds single scattering by a
// statistically significant margin at noon (multiple scattering is a few to tens of percent).
TEST(PathTracer, AllOrdersExceedSingleScattering) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 camera(0, 0, kR), view = dir(60.0, 0), sun = dir(30.0, 180.0);
  PathTraceSettings s;
  s.samples = 200'000;
  const PathTraceResult all = path_trace(m, camera, view, sun, s);
  const glm::dvec3 ss = single_scattering(m, camera, view, sun).radiance;
  for (int c = 0; c < 3; ++c) EXPECT_GT(all.radiance[c] - 2.0 * all.ci95[c], ss[c]);
  EXPECT_GT(all.mean_vertices, 0.0);
}

TEST(PathTracer, NoScatteringMeansNoRadiance) {
  AtmosphereModel m = AtmosphereModel::earth();
  m.rayleigh_scattering = glm::dvec3(0.0);
  m.mie_scattering = glm::dvec3(0.0);  // Mie extinction and ozone stay: pure absorbers.
  PathTraceSettings s;
  s.samples = 20'000;
  s.camera_sees_ground = true;
  for (double view_zenith : {0.0, 90.0, 120.0}) {
    const PathTraceResult pt =
        path_trace(m, glm::dvec3(0, 0, kR + 1.0), dir(view_zenith, 0), dir(30.0, 0), s);
    if (view_zenith < 100.0) {
      EXPECT_EQ(pt.radiance, glm::dvec3(0.0));
      EXPECT_EQ(pt.ci95, glm::dvec3(0.0));
    } else {
      EXPECT_GT(pt.radiance.x, 0.0);  // Only the ground it looks at reflects light.
    }
  }
  s.camera_sees_ground = false;
  EXPECT_EQ(path_trace(m, glm::dvec3(0, 0, kR + 1.0), dir(120.0, 0), dir(30.0, 0), s).radiance,
            glm::dvec3(0.0));
}

// Energy, plane-parallel limit: on a 10^7 km planet with a conservative atmosphere (no
// absorption) over a white Lambertian ground, every photon from the zenith sun leaves through the
// top again, so the upward flux at the top, 2 pi int_0^1 L(-m) m dm, equals the incident flux 1
// in every channel. Gauss-Legendre (2 x 4 nodes) over m; radiance includes the seen ground.
struct Flux {
  glm::dvec3 value{0.0};
  glm::dvec3 ci95{0.0};
};

Flux top_of_atmosphere_upward_flux(const AtmosphereModel& m, std::uint64_t samples) {
  const double x[4] = {0.3399810435848563, 0.8611363115940526, -0.3399810435848563,
                       -0.8611363115940526};
  const double w[4] = {0.6521451548625461, 0.3478548451374538, 0.6521451548625461,
                       0.3478548451374538};
  Flux flux;
  glm::dvec3 variance(0.0);
  for (int panel = 0; panel < 2; ++panel) {  // m in [0, 0.5] and [0.5, 1].
    for (int i = 0; i < 4; ++i) {
      const double m_cos = 0.25 + 0.5 * panel + 0.25 * x[i];
      const double weight = 2.0 * kPi * 0.25 * w[i] * m_cos;
      PathTraceSettings s;
      s.samples = samples;
      s.seed = 100 + panel * 4 + i;
      s.camera_sees_ground = true;
      const glm::dvec3 view(std::sqrt(1.0 - m_cos * m_cos), 0.0, -m_cos);
      const PathTraceResult pt =
          path_trace(m, glm::dvec3(0, 0, m.top_radius_km), view, glm::dvec3(0, 0, 1), s);
      flux.value += weight * pt.radiance;
      variance += weight * weight * (pt.ci95 / 1.96) * (pt.ci95 / 1.96);
    }
  }
  flux.ci95 = 1.96 * glm::sqrt(variance);
  return flux;
}

AtmosphereModel conservative_white(double bottom_radius_km) {
  AtmosphereModel m = AtmosphereModel::earth();
  m.bottom_radius_km = bottom_radius_km;
  m.top_radius_km = bottom_radius_km + 100.0;
  m.absorption_extinction = glm::dvec3(0.0);
  m.mie_extinction = m.mie_scattering;
  m.ground_albedo = glm::dvec3(1.0);
  return m;
}

TEST(PathTracer, ConservativeAtmosphereOverWhiteGroundReflectsAllIncidentFlux) {
  const AtmosphereModel m = conservative_white(1e7);
  const Flux flux = top_of_atmosphere_upward_flux(m, 20'000);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(flux.ci95[c], 0.012);
    // 0.003: angular quadrature and the residual curvature of the planet.
    EXPECT_NEAR(flux.value[c], 1.0, 0.003 + 2.5 * flux.ci95[c]) << "channel " << c;
  }
  // A grey ground absorbs: the flux falls well below 1.
  AtmosphereModel grey = m;
  grey.ground_albedo = glm::dvec3(0.3);
  const Flux lossy = top_of_atmosphere_upward_flux(grey, 5'000);
  for (int c = 0; c < 3; ++c) EXPECT_LT(lossy.value[c], 0.6);
}

// White furnace on the sphere: a conservative atmosphere around a white planet, lit by suns from
// uniformly distributed directions (illuminance 1 each, i.e. uniform radiance 1 / (4 pi)), is in
// equilibrium at radiance 1 / (4 pi) everywhere. A view ending on the ground therefore sees
// exactly 1 / (4 pi); one escaping to space misses the unscattered part, T_view / (4 pi).
// Sun directions are stratified in cos(zenith), two per stratum for an honest variance.
TEST(PathTracer, WhiteFurnaceOnTheSphere) {
  const AtmosphereModel m = conservative_white(6360.0);
  const glm::dvec3 camera(0.0, 0.0, 6361.0);
  std::uint64_t state = 12345;
  auto uniform = [&state] {  // splitmix64, for the sun directions.
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (double view_zenith : {120.0, 60.0}) {
    const bool sees_ground = view_zenith > 90.0;
    const glm::dvec3 view = dir(view_zenith, 0.0);
    const int strata = 8000;
    glm::dvec3 mean(0.0), variance(0.0);
    for (int k = 0; k < strata; ++k) {
      glm::dvec3 pair[2];
      for (int j = 0; j < 2; ++j) {
        const double z = -1.0 + 2.0 * (k + uniform()) / strata, phi = 2.0 * kPi * uniform();
        const double s_z = std::sqrt(1.0 - z * z);
        PathTraceSettings s;
        s.samples = sees_ground ? 8 : 24;  // Most sky-view paths escape unscattered.
        s.seed = 1000 + 2 * k + j;
        s.threads = 1;
        s.camera_sees_ground = true;
        const glm::dvec3 sun(s_z * std::cos(phi), s_z * std::sin(phi), z);
        pair[j] = path_trace(m, camera, view, sun, s).radiance;
      }
      mean += (pair[0] + pair[1]) / (2.0 * strata);
      // Stratum variance (a - b)^2 / 2, over the 2 samples, over strata^2.
      variance += (pair[0] - pair[1]) * (pair[0] - pair[1]) / (4.0 * strata * strata);
    }
    const glm::dvec3 ci95 = 1.96 * glm::sqrt(variance);
    const glm::dvec3 unscattered =
        sees_ground ? glm::dvec3(0.0) : transmittance_to_boundary(m, 6361.0, view.z);
    const glm::dvec3 expected = (1.0 - unscattered) / (4.0 * kPi);
    SCOPED_TRACE(view_zenith);
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(ci95[c], (sees_ground ? 0.01 : 0.02) * expected[c]);
      EXPECT_NEAR(mean[c], expected[c], 2.5 * ci95[c]) << "channel " << c;
    }
  }
}

// A homogeneous ball of radius 10 km around a planet of 1 m (which blocks a negligible solid
// angle and casts a negligible shadow): camera at the centre looking up, sun at the zenith or at
// the nadir. The geometry is axially symmetric, so orders 1 and 2 reduce to nested 1-D integrals,
// written here from the radiative transfer equation with analytic chords, independently of the
// library (l: sun direction, v: view, D: view ray length):
//   L1(x, w) = int_0^d(x,w) exp(-sigma_t t) sum_k sigma_k p_k(w . l) exp(-sigma_t l_sun) dt
//   L2 = int_0^D exp(-sigma_t s) sum_k sigma_k int_sphere p_k(v . w) L1(x_s, w) dw ds.
// With the sun at the nadir the view axis lies in the planet's shadow (L1 = 0 at the camera) and
// all the light has turned by about 180 degrees in two scatterings: a sharp test of how the
// tracer samples and weights the (Cornette-Shanks) phase functions.
constexpr double kBall = 10.0;
constexpr double kSpeck = 0.001;

AtmosphereModel homogeneous_ball() {
  AtmosphereModel m;
  m.bottom_radius_km = kSpeck;
  m.top_radius_km = kBall;
  m.rayleigh_scattering = {0.01, 0.03, 0.06};
  m.rayleigh_density.layers[1] = {.constant_term = 1.0};
  m.mie_scattering = glm::dvec3(0.06);
  m.mie_extinction = glm::dvec3(0.07);
  m.mie_density.layers[1] = {.constant_term = 1.0};
  m.mie_phase = MiePhase::cornette_shanks;
  m.mie_g = 0.8;
  m.ground_albedo = glm::dvec3(0.0);
  return m;
}

// Single scattering arriving at the axis point z from the direction at axial cosine mu, for a sun
// at the zenith (sun_up) or at the nadir.
glm::dvec3 ball_l1(const AtmosphereModel& m, double z, double mu, bool sun_up) {
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  const LocalCoefficients k = m.coefficients(1.0);
  const double cos_sun = sun_up ? mu : -mu;  // w . l
  const glm::dvec3 source = k.rayleigh_scattering * rayleigh_phase(cos_sun) +
                            k.mie_scattering * m.mie_phase_value(cos_sun);
  const double d = -z * mu + std::sqrt(z * z * mu * mu - (z * z - kBall * kBall));
  glm::dvec3 sum(0.0);
  for (int c = 0; c < 3; ++c) {
    sum[c] = testing::gauss_legendre_5(
        [&](double t) {
          const double rho = t * sin_t, pz = z + t * mu;
          const double half = std::sqrt(kBall * kBall - rho * rho);
          const double sun = sun_up ? half - pz : half + pz;  // Chord towards the sun.
          return std::exp(-k.extinction[c] * (t + sun));
        },
        0.0, d, 8);
  }
  return source * sum;
}

TEST(PathTracer, FirstAndSecondOrderMatchNestedQuadratureInAHomogeneousBall) {
  const AtmosphereModel m = homogeneous_ball();
  const LocalCoefficients k = m.coefficients(1.0);
  const glm::dvec3 up(0.0, 0.0, 1.0);
  for (bool sun_up : {true, false}) {
    const glm::dvec3 l1 = sun_up ? ball_l1(m, kSpeck, 1.0, true) : glm::dvec3(0.0);
    glm::dvec3 l2(0.0);
    for (int c = 0; c < 3; ++c) {
      l2[c] = testing::gauss_legendre_5(
          [&](double s) {
            const double z = kSpeck + s;
            const double in_scattered = 2.0 * kPi * testing::integrate_mu_graded([&](double mu) {
                                          const double phase =
                                              k.rayleigh_scattering[c] * rayleigh_phase(mu) +
                                              k.mie_scattering[c] * m.mie_phase_value(mu);
                                          return phase * ball_l1(m, z, mu, sun_up)[c];
                                        });
            return std::exp(-k.extinction[c] * s) * in_scattered;
          },
          0.0, kBall - kSpeck, 6);
    }
    PathTraceSettings s;
    s.samples = sun_up ? 400'000 : 1'500'000;
    s.max_order = 1;
    const PathTraceResult first =
        path_trace(m, glm::dvec3(0, 0, kSpeck), up, up * (sun_up ? 1.0 : -1.0), s);
    s.max_order = 2;
    const PathTraceResult second =
        path_trace(m, glm::dvec3(0, 0, kSpeck), up, up * (sun_up ? 1.0 : -1.0), s);
    SCOPED_TRACE(sun_up ? "sun at the zenith" : "sun at the nadir");
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(second.ci95[c], 0.02 * (l1[c] + l2[c]));
      EXPECT_GT(l2[c], 0.08 * l1[c]);  // Second order matters here: the check has teeth.
      EXPECT_NEAR(first.radiance[c], l1[c], 2.5 * first.ci95[c]) << "channel " << c;
      EXPECT_NEAR(second.radiance[c], l1[c] + l2[c], 2.5 * second.ci95[c]) << "channel " << c;
    }
  }
}

// Russian roulette changes the variance, not the mean. Here absorption keeps path weights well
// below 1, so roulette from the first vertex on kills most paths early.
TEST(PathTracer, RussianRouletteLeavesTheMeanUnchanged) {
  AtmosphereModel m = homogeneous_ball();
  m.mie_extinction = glm::dvec3(0.15);  // Mie single-scattering albedo 0.4.
  const glm::dvec3 camera(0, 0, kSpeck), view = dir(60.0, 0.0), sun = dir(30.0, 90.0);
  PathTraceSettings s;
  s.samples = 300'000;
  s.russian_roulette_start_order = 1;
  const PathTraceResult roulette = path_trace(m, camera, view, sun, s);
  s.russian_roulette_start_order = 1'000'000;
  s.seed = 77;
  const PathTraceResult exhaustive = path_trace(m, camera, view, sun, s);
  EXPECT_LT(roulette.mean_vertices, 0.8 * exhaustive.mean_vertices);
  for (int c = 0; c < 3; ++c) {
    const double ci = std::hypot(roulette.ci95[c], exhaustive.ci95[c]);
    EXPECT_LT(ci, 0.025 * exhaustive.radiance[c]);
    EXPECT_NEAR(roulette.radiance[c], exhaustive.radiance[c], 2.5 * ci) << "channel " << c;
  }
}

TEST(PathTracer, DeterministicForASeedWhateverTheThreadCount) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 camera(0, 0, kR), view = dir(80.0, 0), sun = dir(70.0, 0);
  PathTraceSettings s;
  s.samples = 20'000;
  s.threads = 2;
  const PathTraceResult a = path_trace(m, camera, view, sun, s);
  const PathTraceResult b = path_trace(m, camera, view, sun, s);
  s.threads = 1;
  const PathTraceResult c = path_trace(m, camera, view, sun, s);
  s.threads = 2;
  s.seed = 2;
  const PathTraceResult d = path_trace(m, camera, view, sun, s);
  EXPECT_EQ(a.radiance, b.radiance);
  EXPECT_EQ(a.ci95, b.ci95);
  EXPECT_EQ(a.radiance, c.radiance);
  EXPECT_NE(a.radiance, d.radiance);
}

// The confidence interval shrinks like 1 / sqrt(samples).
TEST(PathTracer, ConfidenceIntervalShrinksWithSamples) {
  const AtmosphereModel m = AtmosphereModel::earth();
  const glm::dvec3 camera(0, 0, kR), view = dir(75.0, 0), sun = dir(45.0, 90.0);
  PathTraceSettings s;
  s.samples = 10'000;
  const PathTraceResult few = path_trace(m, camera, view, sun, s);
  s.samples = 160'000;
  const PathTraceResult many = path_trace(m, camera, view, sun, s);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(many.ci95[c] / few.ci95[c], 0.25, 0.08);
    EXPECT_NEAR(many.radiance[c], few.radiance[c], 2.0 * (few.ci95[c] + many.ci95[c]));
  }
}

// Stiff cases: finite, non-negative output and CI, no truncated path.
TEST(PathTracer, StiffAndExtremeCasesStayFiniteAndNonNegative) {
  const AtmosphereModel earth = AtmosphereModel::earth();
  std::vector<AtmosphereModel> models = {earth, earth.with_density_scale(0.0),
                                         earth.with_density_scale(1000.0), earth.scaled(1.0 / kR),
                                         earth.scaled(100000.0 / kR)};
  for (double g : {0.999, -0.999}) {
    AtmosphereModel m = earth;
    m.mie_g = g;
    models.push_back(m);
  }
  AtmosphereModel tiny = earth;
  tiny.bottom_radius_km = 1.0;
  tiny.top_radius_km = 101.0;
  models.push_back(tiny);
  for (const AtmosphereModel& m : models) {
    const double R = m.bottom_radius_km, H = m.thickness_km();
    for (double altitude : {0.0, -0.5 * std::min(0.1 * H, R), H, 3.0 * H}) {
      for (double view_zenith : {0.0, 90.0, 100.0}) {
        for (double sun_zenith : {0.0, 90.0, 90.5, 120.0}) {
          PathTraceSettings s;
          s.samples = 300;
          s.camera_sees_ground = true;
          const PathTraceResult pt = path_trace(m, glm::dvec3(0, 0, R + altitude),
                                                dir(view_zenith, 0), dir(sun_zenith, 0), s);
          EXPECT_EQ(pt.truncated_paths, 0u);
          for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(pt.radiance[c]) && pt.radiance[c] >= 0.0);
            ASSERT_TRUE(std::isfinite(pt.ci95[c]) && pt.ci95[c] >= 0.0);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace welkin::atmosphere::reference
