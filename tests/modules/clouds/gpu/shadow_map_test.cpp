// The clouds' shadow map against the CPU's copy of the field (double precision over the same noise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "clouds_test_support.h"
#include "validation/cloud_field.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;
using test::noon;
using test::render;

// The optical depth at `t` along a column from its texel's knots, as clouds/shadow_column.glsl reads
// them: linear between the front (0), the depths 0.25, 1, 3 and 8, and the back (the total).
double knots_optical_depth(const float* near, const float* far, double t) {
  const double total = far[2];
  const double d[6] = {near[0], near[1], near[2], near[3], far[0], far[1]};
  const double tau[6] = {
      0.0, std::min(0.25, total), std::min(1.0, total), std::min(3.0, total), std::min(8.0, total), total};
  double sum = 0.0;
  for (int i = 1; i < 6; ++i)
    sum += (tau[i] - tau[i - 1]) * std::clamp((t - d[i - 1]) / std::max(d[i] - d[i - 1], 1e-3), 0.0, 1.0);
  return sum;
}

// Toward a sun 8 degrees up a column crosses 10 km of a cumulus layer: several clouds and the gaps
// between them. A beer shadow map (the first cloud's front, the mean extinction from there to the
// last cloud's back) spreads the far clouds' optical depth over the near ones and the gaps, and puts
// the lit face of the second cloud in the dark; the knots keep where the light is lost.
TEST(CloudsShadowMap, ColumnsThroughSeveralCloudsKeepTheLightBetweenThem) {
  json doc = noon({{"layers", json::array({{{"genus", "cumulus"},
                                            {"base_altitude_m", 1000},
                                            {"thickness_m", 1500},
                                            {"coverage", 0.5},
                                            {"density_per_m", 0.04}}})}});
  test::entity_with(doc, "atmosphere.Sun")["components"]["atmosphere.Sun"]["elevation_deg"] = 8;
  test::Rendered r = render(doc);
  ASSERT_TRUE(r.ran("clouds.shadow_map"));
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  const ImageF map = read_texture_float(*gpu.shadow_map);
  const CloudField field(read_noise(gpu), gpu.block, gpu.layers);
  const ShadowBlock& s = gpu.shadow;
  const int size = map.height / 4;
  ASSERT_EQ(map.width, size * s.cascade_count);
  const glm::dvec3 light(s.light), dir = -light;
  const glm::dvec2 altitudes(gpu.shadow_altitudes_m);

  // Transmittance errors at 48 depths along every 16th column of the two nearer cascades, for the
  // cloud's body (the shape alone) and for the direct beam (the detail noise too).
  double knots_error[2] = {0.0, 0.0}, beer_error = 0.0, lit[2] = {0.0, 0.0};
  int points = 0, multiple = 0;
  for (int k = 0; k < 2; ++k) {
    const auto& c = s.cascades[k];
    const glm::dvec3 u = glm::dvec3(c.axis_u) * double(c.side_m), v = glm::dvec3(c.axis_v) * double(c.side_m);
    for (int j = 8; j < size; j += 16)
      for (int i = 8; i < size; i += 16) {
        const double a = (i + 0.5) / size - 0.5, b = (j + 0.5) / size - 0.5;
        const glm::dvec3 start =
            glm::dvec3(c.origin) + (a * u + b * v) * double(c.side_m) + light * double(c.start_m);
        // The column between the casters' top and base spheres (shadow_map.comp's clouds_column_between).
        const glm::dvec2 outer = field.sphere(start, dir, altitudes.y),
                         inner = field.sphere(start, dir, altitudes.x);
        glm::dvec2 seg = outer;
        if (outer.x > outer.y) continue;
        if (inner.x <= inner.y && inner.x > seg.x) seg.y = std::min(seg.y, inner.x);
        // The CPU's optical depth every 10 m, and its own beer map: front, back, total.
        const double step = 10.0;
        const int n = int(std::ceil((seg.y - seg.x) / step));
        std::vector<double> tau(n + 1, 0.0), eroded(n + 1, 0.0);
        double front = -1.0, back = -1.0;
        int clouds = 0;
        bool inside = false;
        for (int q = 0; q < n; ++q) {
          const double t = seg.x + (q + 0.5) * step;
          const double e = field.extinction(start + dir * t, false);
          tau[q + 1] = tau[q] + e * step;
          eroded[q + 1] = eroded[q] + (e > 0.0 ? field.extinction(start + dir * t, true) : 0.0) * step;
          if (e > 0.0) {
            if (front < 0.0) front = t - 0.5 * step;
            back = t + 0.5 * step;
            clouds += !inside;
          }
          inside = e > 0.0;
        }
        if (front < 0.0) continue;
        multiple += clouds > 1;
        const double mean = tau[n] / std::max(back - front, 1e-3);
        // Read back bottom row first: the texture's row r is the image's 4 size - 1 - r; a column's
        // quarters are the body's near and far halves, then the beam's.
        const float* quarter[4];
        for (int h = 0; h < 4; ++h) quarter[h] = map.pixel(k * size + i, (4 - h) * size - 1 - j);
        for (int p = 0; p < 48; ++p) {
          const double t = seg.x + (p + 0.5) / 48.0 * (seg.y - seg.x);
          const int at = std::min(int((t - seg.x) / step), n);
          const double exact[2] = {std::exp(-tau[at]), std::exp(-eroded[at])};
          const double beer = std::exp(-std::min(tau[n], mean * std::max(t - front, 0.0)));
          for (int m = 0; m < 2; ++m) {
            knots_error[m] +=
                std::abs(std::exp(-knots_optical_depth(quarter[2 * m], quarter[2 * m + 1], t)) - exact[m]);
            lit[m] += exact[m];
          }
          beer_error += std::abs(beer - exact[0]);
          ++points;
        }
      }
  }
  ASSERT_GT(points, 1000);
  EXPECT_GT(multiple, points / 48 / 4) << "columns that cross more than one cloud";
  EXPECT_GT(lit[0], 0.1 * points) << "light along the columns";
  // The eroded field lets more of the beam through than the body: else the two curves are one.
  EXPECT_GT(lit[1], lit[0] * 1.05) << "the beam through the detail";
  // Measured: the knots 0.010 in transmittance on average, a beer map 0.078 (330 of 378 columns
  // cross more than one cloud).
  for (double& e : knots_error) e /= points;
  beer_error /= points;
  std::printf("transmittance error: body %.4f, beam %.4f, beer map %.4f; light: body %.3f, beam %.3f\n",
              knots_error[0], knots_error[1], beer_error, lit[0] / points, lit[1] / points);
  EXPECT_LT(knots_error[0], 0.03);
  EXPECT_LT(knots_error[0], 0.3 * beer_error);
  EXPECT_LT(knots_error[1], 0.03);
}

}  // namespace
}  // namespace welkin::clouds
