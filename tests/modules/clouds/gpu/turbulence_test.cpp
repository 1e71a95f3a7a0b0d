// Curl turbulence on llvmpipe: the curl field the GPU generates (the shape volume's gba) is
// divergence-free on its own grid (measured with central differences over the read-back texels,
// against a field that is not), tileable, deterministic from the seed and scaled to a longest vector
// of 1; it moves where the detail noise is read in a layer's lowest 30% and nowhere above, without
// thinning or thickening the layer; quality low and medium leave it out, as takram does.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clouds_test_support.h"
#include "validation/cloud_field.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

// The curl field as the shaders decode it from the shape volume's gba (2 v / 255 - 1).
struct Field {
  int n;
  const std::vector<uint8_t>& shape;
  double at(int x, int y, int z, int c) const {
    auto wrap = [this](int i) { return ((i % n) + n) % n; };
    return 2.0 * shape[((size_t(wrap(z)) * n + size_t(wrap(y))) * n + size_t(wrap(x))) * 4 + 1 + size_t(c)] / 255.0 - 1.0;
  }
};

// RMS of the central-difference divergence of the components (cx, cy, cz), relative to the RMS of
// the derivative terms it sums.
double relative_divergence(const Field& f, int cx, int cy, int cz) {
  double div2 = 0.0, terms2 = 0.0;
  for (int z = 0; z < f.n; ++z)
    for (int y = 0; y < f.n; ++y)
      for (int x = 0; x < f.n; ++x) {
        const double dx = 0.5 * (f.at(x + 1, y, z, cx) - f.at(x - 1, y, z, cx));
        const double dy = 0.5 * (f.at(x, y + 1, z, cy) - f.at(x, y - 1, z, cy));
        const double dz = 0.5 * (f.at(x, y, z + 1, cz) - f.at(x, y, z - 1, cz));
        div2 += (dx + dy + dz) * (dx + dy + dz);
        terms2 += dx * dx + dy * dy + dz * dz;
      }
  return std::sqrt(div2 / terms2);
}

TEST(CloudsTurbulence, TheCurlVolumeIsDivergenceFreeTileableDeterministicAndScaledToOne) {
  test::Rendered a = test::render(test::noon(), 16, 9);
  const NoiseVolumes na = read_noise(a.world->resource<CloudsGpu>());
  const Field f{na.shape_size, na.shape};

  // Divergence-free up to 8-bit rounding; the same components in another order are not.
  const double solenoidal = relative_divergence(f, 0, 1, 2), control = relative_divergence(f, 1, 2, 0);
  EXPECT_LT(solenoidal, 0.08);
  EXPECT_GT(control, 0.3);
  std::printf("relative divergence: curl field %.2e, components rotated %.2f\n", solenoidal, control);

  // The longest vector has length 1 (half-float precision) and the field is not one spike.
  double longest = 0.0, mean_square = 0.0;
  const int n = f.n;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::dvec3 c(f.at(x, y, z, 0), f.at(x, y, z, 1), f.at(x, y, z, 2));
        longest = std::max(longest, glm::length(c)), mean_square += glm::dot(c, c);
      }
  EXPECT_NEAR(longest, 1.0, 0.01);
  EXPECT_GT(std::sqrt(mean_square / (n * n * n)), 0.25);

  // Tileable: the step from the last slice to the first is like any step between neighbours.
  for (int c = 0; c < 3; ++c) {
    double across = 0.0, inside = 0.0;
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        across += std::abs(f.at(n - 1, y, z, c) - f.at(0, y, z, c)), inside += std::abs(f.at(n / 2, y, z, c) - f.at(n / 2 + 1, y, z, c));
    EXPECT_LT(across, 1.5 * inside) << "component " << c;
  }

  // The same seed gives the same bits, another seed another field.
  test::Rendered b = test::render(test::noon(), 16, 9);
  EXPECT_EQ(read_noise(b.world->resource<CloudsGpu>()).shape, na.shape);
  test::Rendered c = test::render(test::noon({{"seed", 7}}), 16, 9);
  const NoiseVolumes nc = read_noise(c.world->resource<CloudsGpu>());
  EXPECT_NE(Field(nc.shape_size, nc.shape).at(5, 6, 7, 0), f.at(5, 6, 7, 0));
}

// One cumulus layer, 1000-3000 m, at a quality and displacement, seen from 300 m below its base
// looking up (near enough that the march reads the detail noise's finest level).
constexpr double kCameraAltitudeM = 700.0;
json cumulus(const std::string& quality, double displacement_m) {
  json d = test::noon({{"quality", quality},
                       {"turbulence_displacement_m", displacement_m},
                       {"temporal_upscaling", false},
                       {"layers", json::array({{{"genus", "cumulus"}, {"coverage", 0.6}, {"base_altitude_m", 1000},
                                                {"thickness_m", 2000}, {"base_variation_m", 0}}})}});
  for (auto& e : d["entities"])
    if (e["components"].contains("core.Camera"))
      e["components"]["core.Camera"]["pitch_deg"] = 80, e["components"]["core.Camera"]["position_m"] = {0, 0, kCameraAltitudeM};
  return d;
}

TEST(CloudsTurbulence, ItStirsTheBaseLeavesTheTopHalfAndKeepsTheAmountOfCloud) {
  test::Rendered still = test::render(cumulus("high", 0.0), 96, 54);
  test::Rendered stirred = test::render(cumulus("high", 350.0), 96, 54);
  const CloudsGpu& gs = still.world->resource<CloudsGpu>();
  const CloudsGpu& gt = stirred.world->resource<CloudsGpu>();
  EXPECT_EQ(gs.block.turbulence_m, 0.0f);
  EXPECT_EQ(gt.block.turbulence_m, 350.0f);
  const CloudField a(read_noise(gs), gs.block, gs.layers), b(read_noise(gt), gt.block, gt.layers);

  // The layer's full extinction at altitude h (its profile's; base_variation_m is 0): inside a cloud
  // the density rises to it (the genus's edge) and there no erosion, stirred or not, changes it.
  const LayerBlock& L = gs.layers[0];
  auto full = [&](double h) {
    const double t = (h - L.base_m) / L.thickness_m;
    const double profile = std::clamp(L.profile_exp_term * std::exp(L.profile_exponent * t) +
                                          L.profile_linear_term * t + L.profile_constant_term,
                                      0.0, 1.0);
    return profile * L.density_per_m * (gs.block.scattering + gs.block.absorption);
  };
  // A grid of points through the layer's lowest fifth and through its upper half.
  int base_changed = 0, base_cloud_a = 0, base_cloud_b = 0, base_edge = 0, top_changed = 0, top_points = 0;
  const int side = 60;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const glm::dvec3 column(-12000.0 + 400.0 * i + 13.0 * j, -12000.0 + 400.0 * j, 0.0);
      for (double h : {1150.0, 1250.0, 1350.0}) {
        const glm::dvec3 x = column + glm::dvec3(0, 0, h - kCameraAltitudeM);
        const double ea = a.extinction(x), eb = b.extinction(x);
        base_changed += std::abs(ea - eb) > 1e-6;
        base_cloud_a += ea > 0.0, base_cloud_b += eb > 0.0;
        base_edge += (ea > 0.0 && ea < full(h) * (1.0 - 1e-9)) || (eb > 0.0 && eb < full(h) * (1.0 - 1e-9));
      }
      for (double h : {2100.0, 2500.0}) {
        const glm::dvec3 x = column + glm::dvec3(0, 0, h - kCameraAltitudeM);
        top_changed += a.extinction(x) != b.extinction(x);
        ++top_points;
      }
    }
  // Where the base is below full density (its edges and wisps, where the detail noise erodes).
  EXPECT_GT(base_changed, base_edge / 2) << base_edge << " base points below full density";
  EXPECT_EQ(top_changed, 0) << "of " << top_points;
  ASSERT_GT(base_cloud_a, 500);
  EXPECT_NEAR(double(base_cloud_b) / base_cloud_a, 1.0, 0.1);

  // The image changes where the base is seen (looking up at the layer from below).
  const ImageF ia = still.renderer->read_hdr(), ib = stirred.renderer->read_hdr();
  double diff = 0.0, ref = 0.0;
  for (size_t i = 0; i < ia.rgba.size(); ++i)
    if (i % 4 != 3) diff += std::abs(double(ia.rgba[i]) - ib.rgba[i]), ref += std::abs(double(ia.rgba[i]));
  std::printf("base points changed %d of %d with cloud (%d below full density); cloud points %d -> %d; image changed by "
              "%.2f%%\n",
              base_changed, base_cloud_a, base_edge, base_cloud_a, base_cloud_b, 100.0 * diff / ref);
  EXPECT_GT(diff / ref, 0.003);
}

TEST(CloudsTurbulence, LowAndMediumLeaveItOutCustomChooses) {
  EXPECT_EQ(test::render(cumulus("low", 350.0), 8, 4).world->resource<CloudsGpu>().block.turbulence_m, 0.0f);
  EXPECT_EQ(test::render(cumulus("medium", 350.0), 8, 4).world->resource<CloudsGpu>().block.turbulence_m, 0.0f);
  EXPECT_EQ(test::render(cumulus("ultra", 200.0), 8, 4).world->resource<CloudsGpu>().block.turbulence_m, 200.0f);
  json custom = cumulus("custom", 120.0);
  for (auto& e : custom["entities"])
    if (e["components"].contains("clouds.VolumetricClouds")) e["components"]["clouds.VolumetricClouds"]["turbulence"] = false;
  EXPECT_EQ(test::render(custom, 8, 4).world->resource<CloudsGpu>().block.turbulence_m, 0.0f);
}

}  // namespace
}  // namespace welkin::clouds
