// The GPU transmittance LUT against double-precision quadrature: the sibling CPU reference when it
// is built, else a composite Simpson rule here. Both evaluate exp(-optical depth to the top) at the
// (r, mu) each texel stands for (lut_mapping.h mirrors the shader's parameterisation).
#include <algorithm>
#include <cmath>

#include "gpu_test_support.h"
#include "welkin/atmosphere/lut_mapping.h"

#if WELKIN_HAVE_ATMOSPHERE_REFERENCE
#include "reference/ray_geometry.h"
#include "reference/transmittance.h"
#endif

namespace welkin::atmosphere {
namespace {

using nlohmann::json;

double profile_density(const DensityProfile& p, double h) {
  auto layer = [h](const DensityLayer& l) {
    double v = double(l.linear_term_per_km) * h + l.constant_term;
    if (l.exp_term != 0.0f) v += double(l.exp_term) * std::exp(double(l.exp_scale_per_km) * h);
    return std::clamp(v, 0.0, 1.0);
  };
  if (p.empty()) return 0.0;
  if (p.size() == 1) return layer(p[0]);
  return h < p[0].width_km ? layer(p[0]) : layer(p[1]);
}

// Composite Simpson over the path to the top; independent of the reference library.
glm::dvec3 simpson_transmittance(const Atmosphere& a, double r, double mu, int intervals = 4000) {
  double top = a.top_radius_km, bottom = a.bottom_radius_km;
  double d = std::max(0.0, -r * mu + std::sqrt(std::max(0.0, r * r * (mu * mu - 1.0) + top * top)));
  auto sigma = [&](double t) {
    double h = std::sqrt(std::max(0.0, r * r + t * (t + 2.0 * r * mu))) - bottom;
    h = std::max(h, 0.0);
    double dr = profile_density(a.rayleigh_density, h), dm = profile_density(a.mie_density, h),
           da = profile_density(a.absorption_density, h);
    return glm::dvec3(a.rayleigh_scattering) * dr + glm::dvec3(a.mie_extinction) * dm +
           glm::dvec3(a.absorption_extinction) * da;
  };
  double hstep = d / intervals;
  glm::dvec3 sum = sigma(0.0) + sigma(d);
  for (int i = 1; i < intervals; ++i) sum += sigma(i * hstep) * (i % 2 ? 4.0 : 2.0);
  return glm::exp(-sum * hstep / 3.0);
}

glm::dvec3 reference_transmittance(const Atmosphere& a, double r, double mu) {
#if WELKIN_HAVE_ATMOSPHERE_REFERENCE
  const reference::AtmosphereModel m = to_reference(a);
  // The LUT's last column is the horizon itself; rounding must not turn it into a ground hit.
  double mu_h = -std::sqrt(std::max(0.0, 1.0 - (a.bottom_radius_km / r) * (a.bottom_radius_km / r)));
  if (mu <= mu_h) mu = mu_h + 1e-12;
  double d = std::max(
      0.0, -r * mu + std::sqrt(std::max(0.0, r * r * (mu * mu - 1.0) + a.top_radius_km * a.top_radius_km)));
  return glm::exp(-reference::optical_depth(m, r, mu, 0.0, d).value);
#else
  return simpson_transmittance(a, r, mu);
#endif
}

struct LutError {
  double max_abs = 0;  // of transmittance
  // Of optical depth, where 1e-3 < depth < 9.2: below, float rounding of the radius near the top
  // dominates (and moves T by < 1e-6); above, T < 1e-4 and its float value says little.
  double max_rel_depth = 0;
};

LutError transmittance_error(int steps, int width = 64, int height = 32, const json& extra = json::object()) {
  json atm = {
      {"quality", "custom"},           {"transmittance_width", width},  {"transmittance_height", height},
      {"transmittance_steps", steps},  {"multiscattering_size", 4},     {"sky_view_width", 8},
      {"sky_view_height", 8},          {"aerial_perspective_width", 4}, {"aerial_perspective_height", 4},
      {"aerial_perspective_slices", 4}};
  atm.update(extra);
  auto r = test::render(test::scene({{"position_m", {0, 0, 2}}}, atm), 8, 8);
  const Atmosphere a = *r.world->registry().get<Atmosphere>(r.world->registry().first<Atmosphere>());
  ImageF lut = read_texture_float(*r.gpu().transmittance);
  LutError e;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      RadiusMu rm = transmittance_texel_r_mu(x, y, width, height, a.bottom_radius_km, a.top_radius_km);
      glm::dvec3 ref = reference_transmittance(a, rm.r_km, rm.mu);
      const float* g = lut.pixel(x, height - 1 - y);  // readback rows run top to bottom
      for (int c = 0; c < 3; ++c) {
        e.max_abs = std::max(e.max_abs, std::abs(g[c] - ref[c]));
        if (ref[c] > 1e-4 && g[c] > 0.0f) {
          double depth_ref = -std::log(ref[c]), depth_gpu = -std::log(double(g[c]));
          if (depth_ref > 1e-3)
            e.max_rel_depth = std::max(e.max_rel_depth, std::abs(depth_gpu - depth_ref) / depth_ref);
        }
      }
    }
  return e;
}

TEST(TransmittanceLut, MatchesDoublePrecisionQuadratureAtDefaultSettings) {
  // 256 x 64 texels, 40 steps (Hillaire's defaults), Earth. The largest error is in green on rays
  // grazing the ozone tent, whose kinks the midpoint rule resolves only to first order.
  LutError e = transmittance_error(40, 256, 64);
  std::printf(
      "transmittance LUT 256x64, 40 steps: max |dT| = %.3g, max relative optical-depth error = %.3g\n",
      e.max_abs, e.max_rel_depth);
  EXPECT_LT(e.max_abs, 3e-3);
  EXPECT_LT(e.max_rel_depth, 1.5e-2);
}

TEST(TransmittanceLut, ErrorShrinksAsStepsGrow) {
  double previous = INFINITY, first = 0, last = 0, first_depth = 0, last_depth = 0;
  for (int steps : {1, 2, 4, 8, 16, 32, 64, 128}) {
    LutError e = transmittance_error(steps);
    std::printf("steps %4d: max |dT| = %.3g, max relative optical-depth error = %.3g\n", steps, e.max_abs,
                e.max_rel_depth);
    // Midpoint rule: second order until float rounding (about 1e-6 here) takes over.
    EXPECT_LE(e.max_abs, previous * 1.05 + 2e-6) << steps << " steps";
    previous = e.max_abs;
    if (steps == 1) first = e.max_abs, first_depth = e.max_rel_depth;
    last = e.max_abs, last_depth = e.max_rel_depth;
  }
  EXPECT_LT(last, first / 1000.0);
  EXPECT_LT(last_depth, first_depth / 1000.0);
}

#if WELKIN_HAVE_ATMOSPHERE_REFERENCE
TEST(TransmittanceLut, InTestQuadratureAgreesWithTheReference) {
  // The fallback used when the reference is not built is itself checked against it.
  Atmosphere a;
  for (double mu : {1.0, 0.3, 0.02, -0.05})
    for (double r : {6360.01, 6380.0, 6450.0}) {
      if (mu < 0.0 && r * r * (1.0 - mu * mu) < a.bottom_radius_km * a.bottom_radius_km) continue;  // ground
      glm::dvec3 s = simpson_transmittance(a, r, mu), ref = reference_transmittance(a, r, mu);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s[c], ref[c], 1e-6) << "r " << r << " mu " << mu;
    }
}
#endif

TEST(TransmittanceLut, MatchesOnTinyAndHugePlanets) {
  // Earth's optical depths on a planet 6360x smaller (1 km) and ~16x larger (100 000 km).
  for (double scale : {1.0 / 6360.0, 100000.0 / 6360.0}) {
    float k = float(1.0 / scale);
    json atm = {{"bottom_radius_km", 6360.0 * scale},
                {"top_radius_km", 6460.0 * scale},
                {"rayleigh_scattering", {5.802e-3f * k, 13.558e-3f * k, 33.1e-3f * k}},
                {"rayleigh_density", {{{"exp_term", 1}, {"exp_scale_per_km", -k / 8.0f}}}},
                {"mie_scattering", {3.996e-3f * k, 3.996e-3f * k, 3.996e-3f * k}},
                {"mie_extinction", {4.44e-3f * k, 4.44e-3f * k, 4.44e-3f * k}},
                {"mie_density", {{{"exp_term", 1}, {"exp_scale_per_km", -k / 1.2f}}}},
                {"absorption_extinction", {0, 0, 0}}};
    LutError e = transmittance_error(40, 64, 32, atm);
    std::printf("planet radius %.4g km: max |dT| = %.3g, max relative optical-depth error = %.3g\n",
                6360.0 * scale, e.max_abs, e.max_rel_depth);
    EXPECT_LT(e.max_abs, 1.5e-3) << "scale " << scale;
    EXPECT_LT(e.max_rel_depth, 5e-3) << "scale " << scale;
  }
}

}  // namespace
}  // namespace welkin::atmosphere
