// Weather systems on llvmpipe, through the CPU mirror of the field (the GPU's own noise, read back):
// they leave the planet's mean coverage and the scene's own neighbourhood as the layers say, and make
// regions thousands of kilometres apart differ, which the local weather alone (repeating every few
// tens of kilometres) cannot.
#include <cmath>
#include <cstdio>

#include "clouds_test_support.h"
#include "validation/cloud_field.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

constexpr double kLayerMiddleM = 1300.0;  // in the lowest part of a 1000-3000 m layer, below the domes' rounding

struct Field {
  std::unique_ptr<CloudField> field;
  glm::dvec3 camera_from_centre;  // planet-centred camera
  double radius = 0.0;
  // Cloud at the point above the ground at unit direction `up` (planet-centred).
  bool cloud(const glm::dvec3& up) const {
    return field->extinction(up * (radius + kLayerMiddleM) - camera_from_centre) > 0.0;
  }
};

Field field(double amount) {
  json d = test::noon({{"weather_system_amount", amount},
                       {"temporal_upscaling", false},
                       {"layers", json::array({{{"genus", "cumulus"}, {"coverage", 0.45}, {"base_altitude_m", 1000},
                                                {"thickness_m", 2000}, {"base_variation_m", 0}}})}});
  test::Rendered r = test::render(d, 8, 4);
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  Field f;
  f.field = std::make_unique<CloudField>(read_noise(gpu), gpu.block, gpu.layers);
  f.radius = gpu.block.planet_radius_m;
  f.camera_from_centre = glm::dvec3(gpu.block.up) * double(gpu.block.camera_radius_m);
  return f;
}

// A deterministic, even spread of directions over the sphere (Fibonacci lattice).
glm::dvec3 sphere_point(int i, int n) {
  const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// The covered fraction of a square region of side `side_m` around the direction `centre`.
double covered(const Field& f, const glm::dvec3& centre, double side_m, int per_side) {
  const glm::dvec3 e = glm::normalize(glm::cross(std::abs(centre.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1), centre));
  const glm::dvec3 n = glm::cross(centre, e);
  int hits = 0;
  for (int j = 0; j < per_side; ++j)
    for (int i = 0; i < per_side; ++i) {
      const double u = ((i + 0.5) / per_side - 0.5) * side_m / f.radius, v = ((j + 0.5) / per_side - 0.5) * side_m / f.radius;
      hits += f.cloud(glm::normalize(centre + u * e + v * n));
    }
  return double(hits) / (per_side * per_side);
}

TEST(CloudsWeatherSystems, KeepThePlanetsMeanAndTheScenesNeighbourhoodAndMakeRegionsDiffer) {
  const Field local = field(0.0), systems = field(0.5);

  // Over the whole planet: the mean coverage stays the layer's (the sampled mean's standard error is
  // about 0.004); the fraction the eye sees covered rises, the noise eroding thin coverage more.
  const int n = 6000;
  int local_hits = 0, system_hits = 0;
  double mean_coverage = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 up = sphere_point(i, n);
    local_hits += local.cloud(up), system_hits += systems.cloud(up);
    mean_coverage += systems.field->coverage(0, up * (systems.radius + kLayerMiddleM) - systems.camera_from_centre);
  }
  mean_coverage /= n;
  std::printf("planet: mean coverage %.4f; seen covered: local weather %.3f, with weather systems %.3f\n", mean_coverage,
              double(local_hits) / n, double(system_hits) / n);
  EXPECT_NEAR(mean_coverage, 0.45, 0.015);
  EXPECT_GT(local_hits, n / 10);

  // Around the scene's origin (40 km square): the layers' own coverage.
  const glm::dvec3 here = glm::normalize(local.camera_from_centre);
  EXPECT_NEAR(systems.field->coverage(0, glm::dvec3(0.0, 0.0, kLayerMiddleM - 100.0)), 0.45, 0.01);
  const double near_local = covered(local, here, 40000.0, 60), near_systems = covered(systems, here, 40000.0, 60);
  std::printf("around the origin: %.3f and %.3f\n", near_local, near_systems);
  EXPECT_NEAR(near_systems, near_local, 0.03);

  // Regions 200 km wide all over the planet: alike with the local weather alone, spread out with the systems.
  auto spread = [&](const Field& f) {
    double sum = 0.0, sum2 = 0.0;
    const int regions = 40;
    for (int i = 0; i < regions; ++i) {
      const double c = covered(f, sphere_point(i, regions), 200000.0, 14);
      sum += c, sum2 += c * c;
    }
    return std::sqrt(std::max(sum2 / regions - (sum / regions) * (sum / regions), 0.0));
  };
  const double spread_local = spread(local), spread_systems = spread(systems);
  std::printf("spread of regional cover: local %.3f, with systems %.3f\n", spread_local, spread_systems);
  EXPECT_GT(spread_systems, 2.5 * spread_local);
  EXPECT_GT(spread_systems, 0.15);
}

TEST(CloudsWeatherSystems, LeaveClearAndOvercastAlone) {
  for (double g : {0.0, 0.3, 1.0}) {
    EXPECT_EQ(system_coverage(0.0, g, 1.0), 0.0);
    EXPECT_EQ(system_coverage(1.0, g, 1.0), 1.0);
  }
  EXPECT_DOUBLE_EQ(system_coverage(0.3, 0.5, 1.0), 0.3);              // neutral signal
  EXPECT_DOUBLE_EQ(system_coverage(0.5, 0.75, 0.5), 0.5 + 0.5 * 0.5);  // 0.5 + a (2 g - 1) 4 c (1 - c)
}

}  // namespace
}  // namespace welkin::clouds
