// Illuminance of sun and moon outside the atmosphere: inverse-square sun, Allen's full moon and
// the Krisciunas & Schaefer (1991) lunar phase law.
#include "welkin/timeofday/illuminance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "welkin/timeofday/moon.h"

namespace welkin::timeofday {
namespace {

TEST(Illuminance, SunInverseSquare) {
  EXPECT_DOUBLE_EQ(sun_illuminance_lux(1.0), 128000.0);
  // Perihelion is ~6.9% brighter than aphelion (0.9833 vs 1.0167 AU).
  EXPECT_NEAR(sun_illuminance_lux(0.9833) / sun_illuminance_lux(1.0167), 1.069, 0.001);
  EXPECT_THROW(sun_illuminance_lux(0.0), std::invalid_argument);
  EXPECT_THROW(sun_illuminance_lux(std::nan("")), std::invalid_argument);
}

TEST(Illuminance, FullMoonAtMeanDistance) {
  // Allen's Astrophysical Quantities: 0.267 lx for the full moon outside the atmosphere.
  const double full = moon_illuminance_lux(0.0, kMoonMeanDistanceKm, 1.0);
  EXPECT_GE(full, 0.26);
  EXPECT_LE(full, 0.27);
  // A perigee full moon (356 500 km) is ~16% brighter than a mean one.
  EXPECT_NEAR(moon_illuminance_lux(0.0, 356500.0, 1.0) / full, 1.163, 0.002);
}

TEST(Illuminance, KrisciunasSchaeferPhaseLaw) {
  // K&S 1991 eq. 20: magnitudes 0.026 |a| + 4e-9 a^4 fainter than full. At quarter phase this is
  // 2.60 mag, the familiar "a half moon gives about a tenth of the light of a full moon".
  EXPECT_DOUBLE_EQ(moon_phase_law(0.0), 1.0);
  EXPECT_NEAR(-2.5 * std::log10(moon_phase_law(90.0)), 2.602, 0.001);
  EXPECT_GT(moon_phase_law(90.0), 0.08);
  EXPECT_LT(moon_phase_law(90.0), 0.10);
  // Steeper than the lit-area fraction alone (0.5 at quarter): the opposition surge.
  EXPECT_LT(moon_phase_law(90.0), 0.5);
  double previous = 2.0;
  for (double a = 0.0; a <= 180.0; a += 1.0) {
    const double v = moon_phase_law(a);
    EXPECT_LT(v, previous) << a;
    EXPECT_GT(v, 0.0) << a;
    previous = v;
  }
  EXPECT_THROW(moon_phase_law(-1.0), std::invalid_argument);
  EXPECT_THROW(moon_phase_law(181.0), std::invalid_argument);
  EXPECT_THROW(moon_phase_law(std::nan("")), std::invalid_argument);
  EXPECT_THROW(moon_illuminance_lux(0.0, -1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace welkin::timeofday
