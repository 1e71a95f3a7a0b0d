// The LUT method on a handful of representative view rays against the CPU reference, through the
// same code as `welkin probe` and `welkin accuracy` (validation/probe.h): single scattering against
// the quadrature within 2% (sun above 3 degrees, view above 2 degrees), all orders against the
// cached path-traced references. The full sweep and its figures are `welkin accuracy atmosphere`.
#include <algorithm>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "reference/atmosphere_model.h"
#include "reference/gauss_kronrod.h"
#include "validation/accuracy_set.h"
#include "validation/probe.h"
#include "validation/reference_model.h"
#include "welkin/gfx/gl_context.h"

namespace welkin::atmosphere {
namespace {

namespace ref = reference;

GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

ref::ProbeGeometry ray(double altitude_km, double sun_elevation, double view_elevation, double azimuth) {
  return {.altitude_km = altitude_km,
          .view_zenith_deg = 90.0 - view_elevation,
          .view_azimuth_deg = azimuth,
          .sun_zenith_deg = 90.0 - sun_elevation,
          .sun_azimuth_deg = 0.0};
}

double max_rel(const glm::dvec3& value, const glm::dvec3& reference) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(value[c] - reference[c]) / reference[c]);
  return e;
}

std::string describe(const ref::ProbeGeometry& g) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "altitude %g km, sun elevation %g, view elevation %g, azimuth %g",
                g.altitude_km, 90.0 - g.sun_zenith_deg, 90.0 - g.view_zenith_deg, g.view_azimuth_deg);
  return buf;
}

// Daylight at every altitude of the sweep, the horizon at a low sun, straight into the Mie peak.
const ref::ProbeGeometry kRays[] = {ray(0, 30, 10, 90), ray(0, 10, 30, 180), ray(1, 60, 60, 0),
                                    ray(10, 3, 2, 45),  ray(0, 3, 5, 0),     ray(0, 90, 30, 0)};

TEST(AtmosphereAccuracy, SingleScatteringWithinTwoPercentOfQuadrature) {
  gl().make_current();
  const Atmosphere earth;
  GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/true);
  const ref::AtmosphereModel model = to_reference(probe.atmosphere());
  for (const ref::ProbeGeometry& g : kRays) {
    const ProbeValue gpu = probe.evaluate(g), quad = probe_reference(model, g);
    const double e = max_rel(gpu.radiance, quad.radiance);
    std::printf("single scattering, %s: max relative error %.4f\n", describe(g).c_str(), e);
    EXPECT_LT(e, 0.02) << describe(g);
    // Transmittance of the view ray through the LUT: its resolution, not the method, limits it.
    EXPECT_LT(max_rel(gpu.transmittance, quad.transmittance), 0.01) << describe(g);
  }
}

// Twilight radiance per lux of sun is 1e-5 at -6 degrees and 1e-8 to 1e-10 deeper: half floats
// (normal from 6e-5, steps of 6e-8 below) read it as a few steps or zero (measured: red and green 0 at
// -12 degrees, everything 0 at -18). The probe reads at full float precision, so the sky is there
// and darkens smoothly as the sun sinks, in every channel.
TEST(AtmosphereAccuracy, TwilightRadianceIsReadAtFullFloatPrecision) {
  gl().make_current();
  const Atmosphere earth;
  GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/false);
  glm::dvec3 previous(1.0);
  for (double sun : {-6.0, -9.0, -12.0, -15.0, -18.0}) {
    const glm::dvec3 L = probe.evaluate(ray(0.0, sun, 30.0, 180.0)).radiance;
    std::printf("sun %+.0f: radiance %.4g %.4g %.4g\n", sun, L.r, L.g, L.b);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(L[c], 0.0) << "sun " << sun << " channel " << c;
      EXPECT_LT(L[c], previous[c]) << "sun " << sun << " channel " << c;
    }
    previous = L;
  }
}

TEST(AtmosphereAccuracy, AllOrdersAgainstCachedPathTracedReferences) {
  gl().make_current();
  const Atmosphere earth;
  GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/false);
  const ref::AtmosphereModel model = to_reference(probe.atmosphere());
  ReferenceCache cache(model, ReferenceSettings{});
  const auto file =
      std::filesystem::path(WELKIN_SOURCE_DIR) / "modules/atmosphere/validation/accuracy-references.json";
  // A cache made for another planet or other settings is ignored; here that would be a stale file.
  ASSERT_GT(cache.load(file.string()), 0u) << file << " does not match the default atmosphere: regenerate it "
                                           << "with `welkin accuracy atmosphere --cache` (see docs)";
  double sum_sq = 0.0;
  int n = 0;
  for (const ref::ProbeGeometry& g : kRays) {
    const std::optional<CachedReference> pt = cache.find(g);
    ASSERT_TRUE(pt) << describe(g);
    const ProbeValue gpu = probe.evaluate(g);
    const double e = max_rel(gpu.radiance, pt->radiance);
    std::printf("all orders, %s: max relative error %.4f (reference 95%% half-width %.4f)\n",
                describe(g).c_str(), e, max_rel(pt->radiance + pt->ci95, pt->radiance));
    for (int c = 0; c < 3; ++c)
      sum_sq += std::pow((gpu.radiance[c] - pt->radiance[c]) / pt->radiance[c], 2), ++n;
    // The bound, for a sun 3 degrees up or higher (the sweep: 3.5% worst; docs/atmosphere.md).
    EXPECT_LT(e, 0.05) << describe(g);
  }
  const double rmse = std::sqrt(sum_sq / n);
  std::printf("all orders: relative RMSE %.4f over %d channels\n", rmse, n);
  EXPECT_LT(rmse, 0.03);
}

TEST(AtmosphereAccuracy, AllOrdersOverTheSweep) {
  // Every ray of `welkin accuracy atmosphere` at the default quality against the path tracer, by the
  // sun's elevation: the goals at -6 degrees (RMSE <= 4%, worst <= 12%), and the other bands
  // bounded near their measured figures (docs/atmosphere.md), so that a regression shows. With the sun 12
  // degrees down the references' own 95% intervals reach 20%, so there a ray fails only beyond
  // twice its interval plus 15%.
  gl().make_current();
  const Atmosphere earth;
  GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/false);
  ReferenceCache cache(to_reference(probe.atmosphere()), ReferenceSettings{});
  ASSERT_GT(cache.load((std::filesystem::path(WELKIN_SOURCE_DIR) /
                        "modules/atmosphere/validation/accuracy-references.json")
                           .string()),
            0u);
  struct Band {
    const char* name;
    double lowest_sun, worst_allowed, rmse_allowed;
    double worst = 0.0, sum_sq = 0.0;
    int channels = 0;
  };
  Band bands[] = {{"sun >= 3", 3.0, 0.03, 0.01},   {"sun = 0", 0.0, 0.04, 0.015},
                  {"sun = -3", -4.5, 0.08, 0.03},  {"sun = -6", -9.0, 0.12, 0.04},
                  {"sun = -12", -90.0, 1.0, 1.0}};
  for (const ref::ProbeGeometry& g : accuracy_rays()) {
    const double sun_elevation = 90.0 - g.sun_zenith_deg;
    const std::optional<CachedReference> pt = cache.find(g);
    ASSERT_TRUE(pt) << describe(g);
    const glm::dvec3 value = probe.evaluate(g).radiance;
    Band& band = *std::find_if(std::begin(bands), std::end(bands),
                               [&](const Band& b) { return sun_elevation >= b.lowest_sun; });
    const double e = max_rel(value, pt->radiance);
    band.worst = std::max(band.worst, e);
    for (int c = 0; c < 3; ++c)
      band.sum_sq += std::pow((value[c] - pt->radiance[c]) / pt->radiance[c], 2), ++band.channels;
    if (sun_elevation < -9.0) {
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(value[c], pt->radiance[c], 2.0 * pt->ci95[c] + 0.15 * pt->radiance[c])
            << describe(g) << " channel " << c;
    } else {
      EXPECT_LT(e, band.worst_allowed) << describe(g);
    }
  }
  for (const Band& b : bands) {
    ASSERT_GT(b.channels, 0) << b.name;
    const double rmse = std::sqrt(b.sum_sq / b.channels);
    std::printf("%s: RMSE %.4f, worst %.4f over %d channels\n", b.name, rmse, b.worst, b.channels);
    EXPECT_LT(rmse, b.rmse_allowed) << b.name;
  }
}

TEST(AtmosphereAccuracy, MieLegendreMomentsMatchQuadrature) {
  // The closed forms the multi-scattering source uses (components.h) against 2 pi times the
  // integral of the reference's phase functions times P_l.
  for (MiePhase phase : {MiePhase::cornette_shanks, MiePhase::henyey_greenstein})
    for (double g : {-0.9, 0.0, 0.3, 0.76, 0.8, 0.95}) {
      auto p = [&](double c) {
        return phase == MiePhase::henyey_greenstein ? ref::henyey_greenstein_phase(g, c)
                                                    : ref::cornette_shanks_phase(g, c);
      };
      // Breakpoints crowd towards the forward peak, where the integrand varies fastest.
      const double breakpoints[] = {-1.0, 0.0, 0.9, 0.99, 0.999, 1.0};
      const ref::QuadratureResult q = ref::integrate_gauss_kronrod(
          [&](double c) {
            const double p2 = 1.5 * c * c - 0.5;
            return glm::dvec3(p(c), p(c) * c, p(c) * p2) * (2.0 * M_PI);
          },
          breakpoints, ref::QuadratureSettings{.relative_tolerance = 1e-11});
      ASSERT_TRUE(q.converged);
      EXPECT_NEAR(q.value.x, 1.0, 1e-8) << "normalisation, g " << g;
      const glm::dvec2 m = mie_legendre_moments(phase, g);
      EXPECT_NEAR(m.x, q.value.y, 1e-8) << "lambda_1, g " << g << (phase == MiePhase::cornette_shanks ? " CS" : " HG");
      EXPECT_NEAR(m.y, q.value.z, 1e-8) << "lambda_2, g " << g << (phase == MiePhase::cornette_shanks ? " CS" : " HG");
    }
  // Cornette-Shanks at g = 0 is Rayleigh's phase: moments 0 and 1/10, the constants of common.glsl.
  EXPECT_NEAR(mie_legendre_moments(MiePhase::cornette_shanks, 0.0).y, 0.1, 1e-15);
}

TEST(AtmosphereAccuracy, RaymarchConvergesAsStepsGrow) {
  gl().make_current();
  const ref::ProbeGeometry g = ray(0, 30, 10, 90);
  double previous = INFINITY;
  for (int steps : {4, 16, 64}) {
    Atmosphere a;
    a.quality = Quality::custom;
    a.raymarch_steps = steps;
    a.raymarch_light_steps = steps / 4 + 1;
    GpuProbe probe(a, SkyMethod::raymarch, /*single_scattering=*/true);
    const double e = max_rel(probe.evaluate(g).radiance, probe_reference(to_reference(a), g).radiance);
    std::printf("raymarch %d x %d steps: max relative error %.4f\n", steps, steps / 4 + 1, e);
    EXPECT_LT(e, previous) << steps;
    previous = e;
  }
  EXPECT_LT(previous, 0.02);
}

TEST(AtmosphereAccuracy, CachedReferenceIsWhatThePathTracerGives) {
  // Fresh, smaller runs of the same path tracer agree with the cache within twice the two confidence
  // intervals: the cache is a result of this code, not of an older one. A different subset of the
  // sunlit rays each run (chosen from the time; WELKIN_REFERENCE_ROTATION=N repeats a run), so that
  // over the runs a stale entry anywhere in the cache is found, not only on one fixed ray. (Rays with
  // the sun below the horizon are left out: their few scoring paths make a small run's interval too
  // unreliable for a check that must not fail by chance.)
  const Atmosphere earth;
  const ref::AtmosphereModel model = to_reference(earth);
  ReferenceCache cache(model, ReferenceSettings{});
  ASSERT_GT(cache.load((std::filesystem::path(WELKIN_SOURCE_DIR) /
                        "modules/atmosphere/validation/accuracy-references.json")
                           .string()),
            0u);
  std::vector<ref::ProbeGeometry> sunlit;
  for (const ref::ProbeGeometry& g : accuracy_rays())
    if (g.sun_zenith_deg <= 90.0) sunlit.push_back(g);
  const char* fixed = std::getenv("WELKIN_REFERENCE_ROTATION");
  const std::uint64_t rotation = fixed ? std::strtoull(fixed, nullptr, 10) : std::uint64_t(std::time(nullptr));
  std::printf("reference rotation %llu (WELKIN_REFERENCE_ROTATION repeats it)\n", (unsigned long long)rotation);
  std::mt19937_64 pick(rotation);
  for (int k = 0; k < 4; ++k) {
    const ref::ProbeGeometry g = sunlit[pick() % sunlit.size()];
    const std::optional<CachedReference> cached = cache.find(g);
    ASSERT_TRUE(cached.has_value()) << describe(g);
    const CachedReference fresh =
        path_trace_reference(model, g, ReferenceSettings{.samples = 1u << 15, .seed = 7 + rotation}, 2);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(fresh.radiance[c], cached->radiance[c], 2.0 * (fresh.ci95[c] + cached->ci95[c]))
          << describe(g) << " channel " << c;
  }
}

}  // namespace
}  // namespace welkin::atmosphere
