// Stiff and extreme inputs (DESIGN.md, Numerics): every LUT, the froxels, the sky irradiance and the
// rendered frame stay finite, non-negative and bounded. Tiny renders on llvmpipe.
#include "gpu_test_support.h"

namespace welkin::atmosphere {
namespace {

using nlohmann::json;

struct StiffCase {
  std::string name;
  json camera;
  json atmosphere;
  json sun;
};

void PrintTo(const StiffCase& c, std::ostream* os) { *os << c.name; }

json scaled_earth(double radius_km) {
  // Earth's optical depths on a planet of another size: lengths times k, coefficients over k.
  double k = radius_km / 6360.0;
  float inv = float(1.0 / k);
  return {{"bottom_radius_km", radius_km},
          {"top_radius_km", 6460.0 * k},
          {"rayleigh_scattering", {5.802e-3f * inv, 13.558e-3f * inv, 33.1e-3f * inv}},
          {"rayleigh_density", {{{"exp_term", 1}, {"exp_scale_per_km", -inv / 8.0f}}}},
          {"mie_scattering", {3.996e-3f * inv, 3.996e-3f * inv, 3.996e-3f * inv}},
          {"mie_extinction", {4.44e-3f * inv, 4.44e-3f * inv, 4.44e-3f * inv}},
          {"mie_density", {{{"exp_term", 1}, {"exp_scale_per_km", -inv / 1.2f}}}},
          {"absorption_extinction", {0.65e-3f * inv, 1.881e-3f * inv, 0.085e-3f * inv}},
          {"absorption_density",
           {{{"width_km", 25.0 * k}, {"linear_term_per_km", inv / 15.0f}, {"constant_term", -2.0 / 3.0}},
            {{"linear_term_per_km", -inv / 15.0f}, {"constant_term", 8.0 / 3.0}}}},
          {"aerial_perspective_distance_km", 128.0 * k}};
}

json density_scaled(float f) {
  Atmosphere a;
  return {{"rayleigh_scattering",
           {a.rayleigh_scattering.x * f, a.rayleigh_scattering.y * f, a.rayleigh_scattering.z * f}},
          {"mie_scattering", {a.mie_scattering.x * f, a.mie_scattering.y * f, a.mie_scattering.z * f}},
          {"mie_extinction", {a.mie_extinction.x * f, a.mie_extinction.y * f, a.mie_extinction.z * f}},
          {"absorption_extinction",
           {a.absorption_extinction.x * f, a.absorption_extinction.y * f, a.absorption_extinction.z * f}}};
}

json minimal_quality() {
  return {{"quality", "custom"},
          {"transmittance_width", 2},
          {"transmittance_height", 2},
          {"transmittance_steps", 1},
          {"multiscattering_size", 2},
          {"multiscattering_steps", 1},
          {"sky_view_width", 2},
          {"sky_view_height", 2},
          {"sky_view_steps", 1},
          {"aerial_perspective_width", 2},
          {"aerial_perspective_height", 2},
          {"aerial_perspective_slices", 2},
          {"aerial_perspective_steps_per_slice", 1},
          {"raymarch_steps", 1}};
}

json cam(double z_m, double pitch = 5.0) {
  return {{"position_m", {0, 0, z_m}}, {"pitch_deg", pitch}, {"near_m", 0.5}};
}
json sun_at(double elevation) { return {{"elevation_deg", elevation}, {"azimuth_deg", 0}}; }

std::vector<StiffCase> cases() {
  const json earth = json::object();
  std::vector<StiffCase> c = {
      {"noon", cam(2), earth, sun_at(60)},
      {"sun_on_horizon", cam(2), earth, sun_at(0)},
      {"sun_just_below", cam(2), earth, sun_at(-0.3)},
      {"sun_far_below", cam(2), earth, sun_at(-30)},
      {"sun_at_nadir", cam(2), earth, sun_at(-90)},
      {"sun_at_zenith", cam(2, 90), earth, sun_at(90)},
      {"camera_under_ground", cam(-5000), earth, sun_at(20)},
      {"camera_just_below_top", cam(99990, -10), earth, sun_at(10)},
      {"camera_at_top", cam(100000, -10), earth, sun_at(10)},
      {"camera_in_low_orbit_limb", cam(400000, -19.7), earth, sun_at(5)},
      {"camera_far_in_space_nadir", cam(1e7, -90), earth, sun_at(45)},
      {"density_x0", cam(2), density_scaled(0.0f), sun_at(30)},
      {"density_x1000", cam(2), density_scaled(1000.0f), sun_at(30)},
      {"density_x1000_from_space", cam(400000, -60), density_scaled(1000.0f), sun_at(30)},
      {"g_plus_0999_towards_sun",
       {{"position_m", {0, 0, 2}}, {"pitch_deg", 10}},
       {{"mie_g", 0.999}},
       sun_at(10)},
      {"g_minus_0999", cam(2), {{"mie_g", -0.999}}, sun_at(10)},
      {"g_plus_09999_hg",
       {{"position_m", {0, 0, 2}}, {"pitch_deg", 10}},
       {{"mie_g", 0.9999}, {"mie_phase", "henyey_greenstein"}},
       sun_at(10)},
      {"planet_1_km", cam(0.5), scaled_earth(1.0), sun_at(20)},
      {"planet_100000_km", cam(2), scaled_earth(100000.0), sun_at(20)},
      {"minimal_luts_and_steps", cam(2), minimal_quality(), sun_at(20)},
      {"minimal_luts_from_space", cam(400000, -30), minimal_quality(), sun_at(20)},
  };
  // Method raymarch: its own nested march (the light steps), on the cases that stress a march most.
  auto raymarch = [](json a) {
    a["method"] = "raymarch";
    return a;
  };
  json minimal_raymarch = raymarch(minimal_quality());
  minimal_raymarch["raymarch_light_steps"] = 1;
  const std::vector<StiffCase> marched = {
      {"raymarch_noon", cam(2), raymarch(earth), sun_at(60)},
      {"raymarch_sun_just_below", cam(2), raymarch(earth), sun_at(-0.3)},
      {"raymarch_density_x1000", cam(2), raymarch(density_scaled(1000.0f)), sun_at(30)},
      {"raymarch_from_low_orbit", cam(400000, -19.7), raymarch(earth), sun_at(5)},
      {"raymarch_planet_1_km", cam(0.5), raymarch(scaled_earth(1.0)), sun_at(20)},
      {"raymarch_minimal_steps", cam(2), minimal_raymarch, sun_at(20)},
  };
  c.insert(c.end(), marched.begin(), marched.end());
  return c;
}

class StiffCases : public ::testing::TestWithParam<StiffCase> {};

TEST_P(StiffCases, EverythingFiniteNonNegativeBounded) {
  const StiffCase& c = GetParam();
  json doc = test::scene(c.camera, c.atmosphere, c.sun);
  // Geometry 1 km ahead so the aerial-perspective pass has pixels to work on.
  doc["entities"].push_back(
      {{"name", "ball"},
       {"components", {{"core.DebugShape", {{"position_m", {0, 1000, 0}}, {"size_m", {200, 200, 200}}}}}}});
  auto r = test::render(doc, 24, 16);
  AtmosphereGpu& g = r.gpu();
  struct Check {
    const char* what;
    const Texture* texture;
    float max;
  };
  const float half_max = 65504.0f;
  std::vector<Check> checks = {{"transmittance LUT", g.transmittance.get(), 1.0f},
                               {"sky-view LUT", g.sky_view.get(), half_max},
                               {"aerial in-scattering", g.aerial_inscattering.get(), half_max},
                               {"aerial transmittance", g.aerial_transmittance.get(), 1.0f},
                               {"sky irradiance SH", g.sky_irradiance.get(), 1e7f},
                               {"frame (HDR)", &r.renderer->hdr_texture(), half_max}};
  for (const Check& k : checks) {
    test::ImageStats s = test::stats(*k.texture);
    EXPECT_TRUE(s.finite) << c.name << ": " << k.what << " has NaN or inf";
    if (std::string(k.what) == "sky irradiance SH") continue;  // SH coefficients may be negative
    EXPECT_GE(s.min, 0.0f) << c.name << ": " << k.what;
    EXPECT_LE(s.max, k.max * (1.0f + 1e-3f)) << c.name << ": " << k.what;
  }
  // Multi-scattering LUT: the harmonics of a non-negative field L relative to its mean c0, side by
  // side with a one-texel gutter either side (common.glsl): (log c0, Q_yz / c0), (a_z / c0, Q_zz / c0
  // of red), (a_y / c0, Q_zz / c0 of green), (Q_yy / c0, Q_zz / c0 of blue), the irradiance / pi over
  // c0, with a = 3 mean(L w) and Q = 5 mean(L (3/2 w w^T - 1/2)). So |a_i| <= 3 c0, -2.5 <= Q_ii / c0
  // <= 5 and |Q_yz| <= 3.75 c0; the upper hemisphere's irradiance / pi is non-negative and at most 4
  // times the sphere's mean.
  const ImageF ms = read_texture_float(*g.multiscattering);
  const int n = ms.width / kMultiscatteringLayers - 2;
  ASSERT_EQ(n, ms.height);
  const float slack = 1e-2f;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      auto at = [&](int layer, int ch) { return ms.pixel(layer * (n + 2) + 1 + x, y)[ch]; };
      const float k_yz = at(0, 3);
      ASSERT_TRUE(std::isfinite(k_yz)) << c.name << ": multi-scattering LUT Q_yz at " << x << "," << y;
      EXPECT_LE(std::abs(k_yz), 3.75f + slack) << c.name << ": Q_yz at " << x << "," << y;
      for (int ch = 0; ch < 3; ++ch) {
        const float log_c0 = at(0, ch), a_z = at(1, ch), a_y = at(2, ch), k_yy = at(3, ch), k_zz = at(1 + ch, 3),
                    upper = at(4, ch);
        for (float v : {log_c0, a_z, a_y, k_yy, k_zz, upper})
          ASSERT_TRUE(std::isfinite(v)) << c.name << ": multi-scattering LUT texel " << x << "," << y;
        // c0 itself fits the half floats of the LUTs that use it.
        EXPECT_LE(log_c0, std::log(half_max)) << c.name << ": c0 at " << x << "," << y;
        EXPECT_GE(upper, 0.0f) << c.name << ": multi-scattering LUT irradiance at " << x << "," << y;
        EXPECT_LE(upper, 4.0f + 1e-4f) << c.name << ": irradiance at " << x << "," << y;
        EXPECT_LE(std::abs(a_z), 3.0f + 1e-4f) << c.name << ": a_z at " << x << "," << y;
        EXPECT_LE(std::abs(a_y), 3.0f + 1e-4f) << c.name << ": a_y at " << x << "," << y;
        for (float k : {k_zz, k_yy}) {
          EXPECT_GE(k, -2.5f - slack) << c.name << ": Q_zz or Q_yy at " << x << "," << y;
          EXPECT_LE(k, 5.0f + slack) << c.name << ": Q_zz or Q_yy at " << x << "," << y;
        }
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Atmosphere, StiffCases, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<StiffCase>& i) { return i.param.name; });

// Hillaire's per-step integral keeps a very dense atmosphere from gaining energy: no radiance may
// exceed that of a white Lambertian surface under the same sun, E / pi (the headroom covers the
// approximate multiple-scattering series). Seen from the ground (sky-view LUT) and from orbit
// (per-pixel march), where a x1000 atmosphere is a bright, cloud-like deck.
TEST(StiffEnergy, DenseAtmosphereStaysBelowWhiteSurface) {
  const float white = 120000.0f / 3.14159265f;
  for (float f : {1.0f, 10.0f, 100.0f, 1000.0f}) {
    auto ground = test::render(test::scene(cam(2, 20), density_scaled(f), sun_at(30)), 16, 16);
    auto orbit = test::render(test::scene(cam(400000, -90), density_scaled(f), sun_at(30)), 16, 16);
    float from_ground = test::stats(*ground.gpu().sky_view).max;
    float from_orbit = test::stats(read_texture_float(orbit.renderer->hdr_texture())).max;
    std::printf(
        "density x%-5g brightest radiance: sky-view %.4g, seen from orbit %.4g cd/m^2 (white surface %.4g)\n",
        f, from_ground, from_orbit, white);
    EXPECT_LT(from_ground, 1.5f * white) << "density x" << f;
    EXPECT_LT(from_orbit, 1.5f * white) << "density x" << f;
  }
}

}  // namespace
}  // namespace welkin::atmosphere
