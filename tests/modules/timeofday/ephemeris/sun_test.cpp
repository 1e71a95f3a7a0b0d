// NREL SPA (Reda & Andreas 2004, NREL/TP-560-34302) against its worked example (Table A5.1),
// the 2024 seasons and perihelion published by USNO, and the geometry of polar day and night.
#include "welkin/timeofday/sun.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "welkin/timeofday/time.h"

namespace welkin::timeofday {
namespace {

// SPA's example site: NREL, Golden, Colorado, with 820 mbar and 11 C.
constexpr Observer kGolden{.latitude_deg = 39.742476,
                           .longitude_deg = -105.1786,
                           .elevation_m = 1830.14,
                           .pressure_mbar = 820.0,
                           .temperature_c = 11.0};

SolarPosition spa_example() {
  return solar_position(kGolden, UtcTime::parse("2003-10-17T12:30:30-07:00").julian_day(), 67.0);
}

TEST(Spa, ExampleHeliocentricPosition) {
  const SunGeocentric s = spa_example().geocentric;
  EXPECT_NEAR(s.heliocentric_longitude_deg, 24.0182616917, 1e-9);
  EXPECT_NEAR(s.heliocentric_latitude_deg, -0.0001011219, 1e-10);
  EXPECT_NEAR(s.distance_au, 0.9965422974, 1e-9);
}

TEST(Spa, ExampleGeocentricPosition) {
  const SunGeocentric s = spa_example().geocentric;
  EXPECT_NEAR(s.geocentric_longitude_deg, 204.0182616917, 1e-9);
  EXPECT_NEAR(s.geocentric_latitude_deg, 0.0001011219, 1e-10);
  EXPECT_NEAR(s.aberration_deg, -0.005711, 5e-7);
  EXPECT_NEAR(s.apparent_longitude_deg, 204.0085519281, 1e-9);
  EXPECT_NEAR(s.equatorial.ra_deg, 202.22741, 5e-6);
  EXPECT_NEAR(s.equatorial.dec_deg, -9.31434, 5e-6);
}

TEST(Spa, ExampleTopocentricPosition) {
  const TopocentricPosition t = spa_example().topocentric;
  EXPECT_NEAR(t.hour_angle_deg, 11.105900, 5e-6);
  EXPECT_NEAR(t.ra_parallax_deg, -0.000369, 5e-7);
  EXPECT_NEAR(t.equatorial.ra_deg, 202.22704, 5e-6);
  EXPECT_NEAR(t.equatorial.dec_deg, -9.316179, 5e-7);
  EXPECT_NEAR(t.topocentric_hour_angle_deg, 11.10627, 5e-6);
  EXPECT_NEAR(t.true_elevation_deg, 39.872046, 5e-7);
  EXPECT_NEAR(t.refraction_deg, 0.016332, 5e-7);
  EXPECT_NEAR(t.elevation_deg, 39.888378, 5e-7);
}

TEST(Spa, ExampleZenithAndAzimuth) {
  // The headline result of the report: zenith 50.11162, azimuth 194.34024 degrees.
  const TopocentricPosition t = spa_example().topocentric;
  EXPECT_NEAR(t.zenith_deg, 50.11162, 1e-5);
  EXPECT_NEAR(t.azimuth_deg, 194.34024, 1e-5);
}

TEST(Spa, ExampleEquationOfTime) {
  // 14.64 minutes for the example (SPA appendix A.1 as reproduced by pvlib's test-suite).
  EXPECT_NEAR(spa_example().geocentric.equation_of_time_min, 14.64, 0.005);
}

TEST(Spa, SeasonsOf2024) {
  // USNO "Earth's Seasons" for 2024 (UTC, to the minute): the apparent longitude of the sun is 0,
  // 90, 180 and 270 degrees at the equinoxes and solstices. The sun moves 0.0007 deg a minute.
  struct Case {
    const char* instant;
    double longitude;
  };
  const Case cases[] = {{"2024-03-20T03:06:00Z", 0.0},
                        {"2024-06-20T20:51:00Z", 90.0},
                        {"2024-09-22T12:44:00Z", 180.0},
                        {"2024-12-21T09:21:00Z", 270.0}};
  for (const Case& c : cases) {
    const double jd = UtcTime::parse(c.instant).julian_day();
    const double lambda = sun_geocentric(earth_orientation(jd, 69.2)).apparent_longitude_deg;
    EXPECT_NEAR(normalize_degrees_signed(lambda - c.longitude), 0.0, 0.0006) << c.instant;
  }
}

TEST(Spa, PerihelionAndAphelionOf2024) {
  // USNO: perihelion 2024-01-03 00:39 UTC at 0.98331 AU, aphelion 2024-07-05 05:06 UTC at
  // 1.01672 AU.
  const auto distance = [](const char* instant) {
    return sun_geocentric(earth_orientation(UtcTime::parse(instant).julian_day(), 69.2))
        .distance_au;
  };
  EXPECT_NEAR(distance("2024-01-03T00:39:00Z"), 0.98331, 2e-5);
  EXPECT_NEAR(distance("2024-07-05T05:06:00Z"), 1.01672, 2e-5);
  EXPECT_GT(distance("2024-01-01T00:39:00Z"), distance("2024-01-03T00:39:00Z"));
  EXPECT_GT(distance("2024-01-05T00:39:00Z"), distance("2024-01-03T00:39:00Z"));
}

TEST(Spa, PolarDayAndNight) {
  // At the poles the sun's elevation is its declination, so it stays ~23.4 degrees above the
  // horizon through the June solstice day at the North Pole and below it in December.
  const Observer north{.latitude_deg = 90.0, .longitude_deg = 0.0};
  const Observer south{.latitude_deg = -90.0, .longitude_deg = 0.0};
  const UtcTime june = UtcTime::parse("2024-06-20T00:00:00Z");
  const UtcTime december = UtcTime::parse("2024-12-21T00:00:00Z");
  for (int step = 0; step <= 48; ++step) {
    const double seconds = step * 1800.0;
    const double jd_june = june.plus_seconds(seconds).julian_day();
    const double jd_december = december.plus_seconds(seconds).julian_day();
    EXPECT_GT(solar_position(north, jd_june, 69.2).topocentric.elevation_deg, 23.0);
    EXPECT_LT(solar_position(north, jd_december, 69.2).topocentric.elevation_deg, -23.0);
    EXPECT_LT(solar_position(south, jd_june, 69.2).topocentric.elevation_deg, -23.0);
    EXPECT_GT(solar_position(south, jd_december, 69.2).topocentric.elevation_deg, 23.0);
  }
}

TEST(Spa, DateLineLongitudesAgree) {
  Observer east = kGolden;
  Observer west = kGolden;
  east.longitude_deg = 180.0;
  west.longitude_deg = -180.0;
  for (double jd = 2460000.5; jd < 2460003.0; jd += 0.0937) {
    const TopocentricPosition a = solar_position(east, jd, 69.0).topocentric;
    const TopocentricPosition b = solar_position(west, jd, 69.0).topocentric;
    EXPECT_NEAR(a.elevation_deg, b.elevation_deg, 1e-9);
    EXPECT_NEAR(normalize_degrees_signed(a.azimuth_deg - b.azimuth_deg), 0.0, 1e-9);
  }
}

TEST(Spa, RefractionFollowsPressureAndTemperature) {
  const RefractionSettings sun = sun_refraction_settings();
  // About 1 arc-minute at 45 degrees for standard air (Saemundsson's formula, SPA eq. 42).
  EXPECT_NEAR(refraction_correction_deg(45.0, 1010.0, 10.0, sun) * 60.0, 1.0, 0.03);
  EXPECT_DOUBLE_EQ(refraction_correction_deg(10.0, 0.0, 10.0, sun), 0.0);     // no air
  EXPECT_DOUBLE_EQ(refraction_correction_deg(-5.0, 1010.0, 10.0, sun), 0.0);  // below cut-off
  EXPECT_DOUBLE_EQ(refraction_correction_deg(10.0, 1010.0, 10.0, sun_refraction_settings(false)),
                   0.0);
  EXPECT_GT(refraction_correction_deg(0.0, 1010.0, 10.0, sun),
            refraction_correction_deg(5.0, 1010.0, 10.0, sun));
  EXPECT_GT(refraction_correction_deg(5.0, 1010.0, -20.0, sun),
            refraction_correction_deg(5.0, 1010.0, 30.0, sun));
}

TEST(Spa, RejectsBadInput) {
  const double jd = 2452930.312847;
  Observer bad = kGolden;
  bad.latitude_deg = 90.5;
  EXPECT_THROW(solar_position(bad, jd, 67.0), std::invalid_argument);
  bad = kGolden;
  bad.longitude_deg = std::nan("");
  EXPECT_THROW(solar_position(bad, jd, 67.0), std::invalid_argument);
  EXPECT_THROW(solar_position(kGolden, std::nan(""), 67.0), std::invalid_argument);
  EXPECT_THROW(solar_position(kGolden, jd, INFINITY), std::invalid_argument);
  // SPA is stated for -2000..6000.
  EXPECT_THROW(solar_position(kGolden, julian_day(6001, 1, 1.5), 0.0), std::invalid_argument);
  EXPECT_THROW(solar_position(kGolden, julian_day(-2001, 12, 31.5), 0.0), std::invalid_argument);
  EXPECT_NO_THROW(solar_position(kGolden, julian_day(6000, 12, 31.5), 0.0));
  EXPECT_NO_THROW(solar_position(kGolden, julian_day(-2000, 1, 1.5), 0.0));
}

}  // namespace
}  // namespace welkin::timeofday
