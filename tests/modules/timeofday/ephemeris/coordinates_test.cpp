// Coordinate helpers against Meeus examples 13.a (ecliptic to equatorial) and 17.a (angular
// separation), and the East-North-Up convention.
#include "welkin/timeofday/coordinates.h"

#include <gtest/gtest.h>

#include <cmath>

namespace welkin::timeofday {
namespace {

TEST(Coordinates, NormalizeDegrees) {
  EXPECT_DOUBLE_EQ(normalize_degrees(370.0), 10.0);
  EXPECT_DOUBLE_EQ(normalize_degrees(-10.0), 350.0);
  EXPECT_DOUBLE_EQ(normalize_degrees(-1e-18), 0.0);
  EXPECT_LT(normalize_degrees(-1e-18), 360.0);
  EXPECT_DOUBLE_EQ(normalize_degrees(720.0), 0.0);
  EXPECT_DOUBLE_EQ(normalize_degrees_signed(190.0), -170.0);
  EXPECT_DOUBLE_EQ(normalize_degrees_signed(180.0), 180.0);
  EXPECT_DOUBLE_EQ(normalize_degrees_signed(-180.0), 180.0);
}

TEST(Coordinates, MeeusExample13aPollux) {
  // Pollux: lambda 113.215630, beta 6.684170 at epsilon 23.4392911 gives alpha 116.328942,
  // delta 28.026183 degrees.
  const Equatorial e = ecliptic_to_equatorial(113.215630, 6.684170, 23.4392911);
  EXPECT_NEAR(e.ra_deg, 116.328942, 2e-6);
  EXPECT_NEAR(e.dec_deg, 28.026183, 2e-6);
}

TEST(Coordinates, MeeusExample17aArcturusSpica) {
  // Arcturus and Spica are 32.7930 degrees apart.
  EXPECT_NEAR(angular_separation_deg({213.9154, 19.1825}, {201.2983, -11.1614}), 32.7930, 1e-4);
}

TEST(Coordinates, SeparationStaysAccurateAtArcSeconds) {
  const double one_arcsec = 1.0 / 3600.0;
  EXPECT_NEAR(angular_separation_deg({10.0, 20.0}, {10.0, 20.0 + one_arcsec}), one_arcsec, 1e-12);
  EXPECT_DOUBLE_EQ(angular_separation_deg({10.0, 20.0}, {10.0, 20.0}), 0.0);
  EXPECT_NEAR(angular_separation_deg({0.0, 0.0}, {180.0, 0.0}), 180.0, 1e-12);
}

TEST(Coordinates, EastNorthUp) {
  const auto north = enu_direction(0.0, 0.0);
  EXPECT_NEAR(north[0], 0.0, 1e-15);
  EXPECT_NEAR(north[1], 1.0, 1e-15);
  EXPECT_NEAR(north[2], 0.0, 1e-15);
  const auto east = enu_direction(90.0, 0.0);
  EXPECT_NEAR(east[0], 1.0, 1e-15);
  EXPECT_NEAR(east[1], 0.0, 1e-15);
  const auto west_up = enu_direction(270.0, 30.0);
  EXPECT_NEAR(west_up[0], -std::cos(30.0 * kDegToRad), 1e-15);
  EXPECT_NEAR(west_up[2], 0.5, 1e-15);
  const auto zenith = enu_direction(123.0, 90.0);
  EXPECT_NEAR(zenith[2], 1.0, 1e-15);
  for (double az = 0.0; az < 360.0; az += 17.0) {
    for (double el = -90.0; el <= 90.0; el += 13.0) {
      const auto v = enu_direction(az, el);
      EXPECT_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.0, 1e-14);
    }
  }
}

}  // namespace
}  // namespace welkin::timeofday
