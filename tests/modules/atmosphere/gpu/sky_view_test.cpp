// The sky-view LUT's march against the CPU reference's single scattering (multiple scattering and
// the ground switched off, so both compute the same integral): phase functions, sun transmittance
// through the LUT, the per-step integral and the LUT's parameterisation, all at once.
#include <cmath>

#include "gpu_test_support.h"
#include "welkin/atmosphere/lut_mapping.h"

#if WELKIN_HAVE_ATMOSPHERE_REFERENCE
#include "reference/single_scattering.h"
#endif

namespace welkin::atmosphere {
namespace {

using nlohmann::json;

#if WELKIN_HAVE_ATMOSPHERE_REFERENCE

struct SkyError {
  double max_rel = 0;  // over the sampled texels and channels
};

// Relative error of the sky-view LUT (illuminance 1) against quadrature, over texels above the
// horizon spread across the LUT.
SkyError sky_view_error(int steps, double sun_elevation_deg, const json& extra = json::object()) {
  const int w = 32, h = 32;
  json atm = {{"quality", "custom"},           {"multiple_scattering_factor", 0},
              {"ground_albedo", {0, 0, 0}},    {"transmittance_width", 512},
              {"transmittance_height", 128},   {"transmittance_steps", 256},
              {"multiscattering_size", 4},     {"sky_view_width", w},
              {"sky_view_height", h},          {"sky_view_steps", steps},
              {"aerial_perspective_width", 4}, {"aerial_perspective_height", 4},
              {"aerial_perspective_slices", 4}};
  atm.update(extra);
  json sun = {{"elevation_deg", sun_elevation_deg}, {"azimuth_deg", 0}, {"illuminance_lux", 1.0}};
  auto r = test::render(test::scene({{"position_m", {0, 0, 200}}}, atm, sun), 8, 8);
  const Atmosphere a = *r.world->registry().get<Atmosphere>(r.world->registry().first<Atmosphere>());
  const reference::AtmosphereModel model = to_reference(a);
  const FrameBlock& u = r.gpu().uniforms;
  const glm::dvec3 camera(u.camera_km), sun_dir(u.sun_direction);
  const glm::dmat3 frame(u.sky_frame);
  ImageF lut = read_texture_float(*r.gpu().sky_view);
  SkyError e;
  for (int y = 1; y < h / 2 - 1; y += 3)  // above the horizon, away from its texel row
    for (int x = 0; x < w; x += 5) {
      ZenithAzimuth za = sky_view_texel_direction(x, y, w, h, glm::length(camera), a.bottom_radius_km);
      double s = std::sqrt(std::max(0.0, 1.0 - za.cos_zenith * za.cos_zenith));
      glm::dvec3 dir = frame * glm::dvec3(std::cos(za.azimuth) * s, std::sin(za.azimuth) * s, za.cos_zenith);
      glm::dvec3 ref = reference::single_scattering(model, camera, dir, sun_dir).radiance;
      const float* g = lut.pixel(x, h - 1 - y);
      for (int c = 0; c < 3; ++c)
        if (ref[c] > 1e-6) e.max_rel = std::max(e.max_rel, std::abs(g[c] - ref[c]) / ref[c]);
    }
  return e;
}

TEST(SkyViewLut, SingleScatteringConvergesToReference) {
  for (double elevation : {30.0, 2.0}) {
    double previous = INFINITY, first = 0, last = 0;
    for (int steps : {2, 4, 8, 16, 32, 64, 128}) {
      SkyError e = sky_view_error(steps, elevation);
      std::printf("sun %4.1f deg, %3d steps: max relative error %.3g\n", elevation, steps, e.max_rel);
      EXPECT_LE(e.max_rel, previous * 1.1 + 2e-3) << steps << " steps, sun " << elevation;
      previous = e.max_rel;
      if (steps == 2) first = e.max_rel;
      last = e.max_rel;
    }
    EXPECT_LT(last, first / 10.0);
    // Floor: half-float storage, bilinear transmittance LUT and float geometry.
    EXPECT_LT(last, 1e-2) << "sun " << elevation;
  }
}

TEST(SkyViewLut, DefaultStepsWithinStatedTolerance) {
  // Hillaire's 30 steps with the quadratic distribution: about 1%, largest near the horizon.
  SkyError e = sky_view_error(30, 30.0);
  std::printf("30 steps, sun 30 deg: max relative error %.3g\n", e.max_rel);
  EXPECT_LT(e.max_rel, 2e-2);
}

TEST(SkyViewLut, PhaseFunctionsMatchReference) {
  for (const char* phase : {"cornette_shanks", "henyey_greenstein"})
    for (double g : {0.0, 0.5, -0.7}) {
      SkyError e = sky_view_error(128, 20.0, {{"mie_phase", phase}, {"mie_g", g}});
      EXPECT_LT(e.max_rel, 1e-2) << phase << " g=" << g;
    }
}

#else
TEST(SkyViewLut, NeedsTheCpuReference) { GTEST_SKIP() << "welkin_atmosphere_reference is not built"; }
#endif

}  // namespace
}  // namespace welkin::atmosphere
