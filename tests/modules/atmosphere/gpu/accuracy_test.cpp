// The LUT method on a handful of representative view rays against the CPU reference, through the
// same code as `welkin probe` and `welkin accuracy` (validation/probe.h): single scattering against
// the quadrature within 2% (sun above 3 degrees, view above 2 degrees), all orders against the
// cached path-traced references. The full sweep and its figures are `welkin accuracy atmosphere`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

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
  std::snprintf(buf, sizeof buf, "altitude %g km, sun elevation %g, view elevation %g, azimuth %g", g.altitude_km,
                90.0 - g.sun_zenith_deg, 90.0 - g.view_zenith_deg, g.view_azimuth_deg);
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

TEST(AtmosphereAccuracy, AllOrdersAgainstCachedPathTracedReferences) {
  gl().make_current();
  const Atmosphere earth;
  GpuProbe probe(earth, SkyMethod::lut, /*single_scattering=*/false);
  const ref::AtmosphereModel model = to_reference(probe.atmosphere());
  ReferenceCache cache(model, ReferenceSettings{});
  const auto file = std::filesystem::path(WELKIN_SOURCE_DIR) / "modules/atmosphere/validation/accuracy-references.json";
  // A cache made for another planet or other settings is ignored; here that would be a stale file.
  ASSERT_GT(cache.load(file.string()), 0u) << file << " does not match the default atmosphere: regenerate it "
                                           << "with `welkin accuracy atmosphere --cache` (README)";
  double sum_sq = 0.0;
  int n = 0;
  for (const ref::ProbeGeometry& g : kRays) {
    const std::optional<CachedReference> pt = cache.find(g);
    ASSERT_TRUE(pt) << describe(g);
    const ProbeValue gpu = probe.evaluate(g);
    const double e = max_rel(gpu.radiance, pt->radiance);
    std::printf("all orders, %s: max relative error %.4f (reference 95%% half-width %.4f)\n", describe(g).c_str(), e,
                max_rel(pt->radiance + pt->ci95, pt->radiance));
    for (int c = 0; c < 3; ++c) sum_sq += std::pow((gpu.radiance[c] - pt->radiance[c]) / pt->radiance[c], 2), ++n;
    // Hillaire's isotropic multiple scattering: 5% is met in daylight from a sun at 10 degrees up,
    // not at a low sun's horizon (blue up to 13.5% low) nor a high sun's red (up to 9% high). The
    // bounds are the sweep's measured worst cases (README, `welkin accuracy atmosphere`).
    const double sun_elevation = 90.0 - g.sun_zenith_deg;
    EXPECT_LT(e, sun_elevation >= 10.0 && sun_elevation <= 30.0 ? 0.05 : 0.14) << describe(g);
  }
  const double rmse = std::sqrt(sum_sq / n);
  std::printf("all orders: relative RMSE %.4f over %d channels\n", rmse, n);
  EXPECT_LT(rmse, 0.05);
}

TEST(AtmosphereAccuracy, CachedReferenceIsWhatThePathTracerGives) {
  // A fresh, smaller run of the same path tracer agrees with the cache within the two confidence
  // intervals: the cache is a result of this code, not of an older one.
  const Atmosphere earth;
  const ref::AtmosphereModel model = to_reference(earth);
  ReferenceCache cache(model, ReferenceSettings{});
  ASSERT_GT(cache.load((std::filesystem::path(WELKIN_SOURCE_DIR) /
                        "modules/atmosphere/validation/accuracy-references.json")
                           .string()),
            0u);
  const ref::ProbeGeometry g = ray(0, 30, 10, 90);
  const CachedReference cached = *cache.find(g);
  const CachedReference fresh =
      path_trace_reference(model, g, ReferenceSettings{.samples = 1u << 15, .seed = 7}, 2);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(fresh.radiance[c], cached.radiance[c], 1.5 * (fresh.ci95[c] + cached.ci95[c])) << c;
}

}  // namespace
}  // namespace welkin::atmosphere
