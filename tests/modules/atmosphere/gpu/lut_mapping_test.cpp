// The LUT parameterisations' texel mappings (lut_mapping.h, mirrored by common.glsl): the mapping the
// shaders look up with must be the exact inverse of the one the LUTs are filled with, so that a
// lookup at a texel's own parameter lands on the texel's centre. (They once disagreed by
// (x - 0.5) / (n + 1) texels.)
#include <gtest/gtest.h>

#include "welkin/atmosphere/lut_mapping.h"

namespace welkin::atmosphere {
namespace {

TEST(LutMapping, TexelCentresAndUnitParametersRoundTripExactly) {
  for (int n : {2, 4, 32, 64, 256}) {
    EXPECT_DOUBLE_EQ(unit_to_sub_uv(0.0, n), 0.5 / n) << n;          // the first texel's centre
    EXPECT_DOUBLE_EQ(unit_to_sub_uv(1.0, n), (n - 0.5) / n) << n;    // the last texel's centre
    for (int i = 0; i < n; ++i) {
      const double centre = (i + 0.5) / n, unit = sub_uv_to_unit(centre, n);
      EXPECT_NEAR(unit, double(i) / (n - 1), 1e-15) << n << " " << i;
      EXPECT_NEAR(unit_to_sub_uv(unit, n), centre, 1e-15) << n << " " << i;
    }
    for (double u : {0.1, 0.25, 0.5, 0.9}) EXPECT_NEAR(sub_uv_to_unit(unit_to_sub_uv(u, n), n), u, 1e-15);
  }
}

TEST(LutMapping, TransmittanceLookupOfATexelsOwnRadiusAndAngleLandsOnItsCentre) {
  const double bottom = 6360.0, top = 6460.0;
  for (auto [w, h] : {std::pair{256, 64}, std::pair{64, 32}, std::pair{8, 4}}) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const RadiusMu rm = transmittance_texel_r_mu(x, y, w, h, bottom, top);
        const TextureUv uv = transmittance_uv(rm.r_km, rm.mu, w, h, bottom, top);
        // In texels: float LUTs are read bilinearly, so a thousandth of a texel is far below what
        // filtering resolves; the old mapping missed by up to half a texel over (n + 1).
        EXPECT_NEAR(uv.u * w, x + 0.5, 1e-6) << w << "x" << h << " texel " << x << "," << y;
        EXPECT_NEAR(uv.v * h, y + 0.5, 1e-6) << w << "x" << h << " texel " << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace welkin::atmosphere
