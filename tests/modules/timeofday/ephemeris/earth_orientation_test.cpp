// Nutation, obliquity and sidereal time against the SPA report (Reda & Andreas 2004, Table A5.1
// intermediate values) and Meeus examples 12.a, 12.b and 22.a.
#include "welkin/timeofday/earth_orientation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "welkin/timeofday/time.h"

namespace welkin::timeofday {
namespace {

constexpr double kArcsec = 1.0 / 3600.0;

// The SPA example: 2003-10-17 19:30:30 UT, Delta-T 67 s. The report prints JD 2452930.312847,
// rounded; sidereal time moves 0.36 degree per 1e-3 day, so the exact instant is used.
EarthOrientation spa_example() {
  return earth_orientation(UtcTime::parse("2003-10-17T19:30:30Z").julian_day(), 67.0);
}

TEST(EarthOrientation, SpaExampleTimeScales) {
  const EarthOrientation e = spa_example();
  EXPECT_NEAR(e.jde, 2452930.313623, 5e-7);
  EXPECT_NEAR(e.jc, 0.0379277986858, 1e-10);
  EXPECT_NEAR(e.jce, 0.037927819916852, 1e-10);
  EXPECT_NEAR(e.jme, 0.003792781991685, 1e-11);
}

TEST(EarthOrientation, SpaExampleNutationArguments) {
  const LunisolarArguments x = spa_example().arguments;
  EXPECT_NEAR(x.moon_mean_elongation_deg, 17185.861179, 1e-5);
  EXPECT_NEAR(x.sun_mean_anomaly_deg, 1722.893218, 1e-5);
  EXPECT_NEAR(x.moon_mean_anomaly_deg, 18234.075703, 1e-5);
  EXPECT_NEAR(x.moon_argument_of_latitude_deg, 18420.071012, 1e-5);
  EXPECT_NEAR(x.moon_ascending_node_deg, 51.686951, 1e-6);
}

TEST(EarthOrientation, SpaExampleNutationAndObliquity) {
  const EarthOrientation e = spa_example();
  EXPECT_NEAR(e.nutation.longitude_deg, -0.00399840, 5e-9);
  EXPECT_NEAR(e.nutation.obliquity_deg, 0.00166657, 5e-9);
  EXPECT_NEAR(e.mean_obliquity_deg * 3600.0, 84379.672625, 1e-6);
  EXPECT_NEAR(e.true_obliquity_deg, 23.440465, 5e-7);
}

TEST(EarthOrientation, SpaExampleSiderealTime) {
  const EarthOrientation e = spa_example();
  EXPECT_NEAR(e.mean_sidereal_time_deg, 318.515579, 2e-6);
  EXPECT_NEAR(e.apparent_sidereal_time_deg, 318.511910, 2e-6);
}

TEST(EarthOrientation, MeeusExample22a) {
  // 1987 April 10, 0h TD.
  const EarthOrientation e = earth_orientation(2446895.5, 0.0);
  EXPECT_NEAR(e.nutation.longitude_deg / kArcsec, -3.788, 0.001);
  EXPECT_NEAR(e.nutation.obliquity_deg / kArcsec, 9.443, 0.001);
  EXPECT_NEAR(e.mean_obliquity_deg, 23.0 + 26.0 / 60.0 + 27.407 / 3600.0, 0.001 * kArcsec);
  EXPECT_NEAR(e.true_obliquity_deg, 23.0 + 26.0 / 60.0 + 36.850 / 3600.0, 0.001 * kArcsec);
}

TEST(EarthOrientation, MeeusExample12aSiderealTimeAtZeroUt) {
  // 1987 April 10, 0h UT: mean 13h10m46.3668s, apparent 13h10m46.1351s.
  const EarthOrientation e = earth_orientation(julian_day(1987, 4, 10.0), 0.0);
  const double seconds_of_time = 1.0 / 240.0;  // degrees per second of sidereal time
  EXPECT_NEAR(e.mean_sidereal_time_deg, (13.0 * 3600 + 10 * 60 + 46.3668) * seconds_of_time,
              1e-4 * seconds_of_time);
  EXPECT_NEAR(e.apparent_sidereal_time_deg, (13.0 * 3600 + 10 * 60 + 46.1351) * seconds_of_time,
              1e-4 * seconds_of_time);
}

TEST(EarthOrientation, MeeusExample12bSiderealTimeAtAnyInstant) {
  // 1987 April 10, 19h21m00s UT: 128.737873 degrees = 8h34m57.0896s.
  const double jd = UtcTime::parse("1987-04-10T19:21:00Z").julian_day();
  EXPECT_NEAR(mean_sidereal_time_deg(jd), 128.737873, 2e-6);
}

TEST(EarthOrientation, ApparentAndMeanSiderealTimeDifferByEquationOfEquinoxes) {
  // The equation of the equinoxes never exceeds ~1.2 seconds of time (0.005 degree).
  for (double jd = 2415020.5; jd < 2488070.5; jd += 997.3) {
    const EarthOrientation e = earth_orientation(jd, 60.0);
    double d = e.apparent_sidereal_time_deg - e.mean_sidereal_time_deg;
    if (d > 180.0) d -= 360.0;
    if (d < -180.0) d += 360.0;
    EXPECT_LT(std::abs(d), 0.0055) << jd;
  }
}

}  // namespace
}  // namespace welkin::timeofday
