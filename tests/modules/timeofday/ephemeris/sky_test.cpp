// compute_sky: the one entry point, checked against SPA's example, for agreement with the parts it
// is built from, for clear errors on bad input and for bounded output on extreme input.
#include "welkin/timeofday/sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/delta_t.h"
#include "welkin/timeofday/sun.h"

namespace welkin::timeofday {
namespace {

constexpr Observer kGolden{.latitude_deg = 39.742476,
                           .longitude_deg = -105.1786,
                           .elevation_m = 1830.14,
                           .pressure_mbar = 820.0,
                           .temperature_c = 11.0};

std::string error_of(const Observer& observer, const UtcTime& time,
                     const EphemerisOptions& options = {}) {
  std::string error;
  EXPECT_FALSE(try_compute_sky(observer, time, options, &error).has_value());
  EXPECT_THROW(compute_sky(observer, time, options), std::invalid_argument);
  return error;
}

TEST(ComputeSky, SpaExample) {
  const SkyState sky =
      compute_sky(kGolden, UtcTime::parse("2003-10-17T12:30:30-07:00"), {.delta_t_s = 67.0});
  EXPECT_NEAR(sky.julian_day, 2452930.312847, 5e-7);
  EXPECT_NEAR(sky.sun.zenith_deg, 50.11162, 1e-5);
  EXPECT_NEAR(sky.sun.azimuth_deg, 194.34024, 1e-5);
  EXPECT_NEAR(sky.sun.elevation_deg, 39.888378, 1e-6);
  EXPECT_NEAR(sky.sun.distance_au, 0.9965422974, 1e-9);
  EXPECT_NEAR(sky.sun.ra_deg, 202.22741, 5e-6);
  EXPECT_NEAR(sky.sun.dec_deg, -9.31434, 5e-6);
  EXPECT_NEAR(sky.sun.illuminance_lux, 128000.0 / (0.9965422974 * 0.9965422974), 0.01);
  EXPECT_DOUBLE_EQ(sky.sun_visible_fraction, 1.0);
  // Sun semi-diameter 959.63" / R (Meeus ch. 55).
  EXPECT_NEAR(sky.sun.angular_radius_deg, 959.63 / 3600.0 / 0.9965422974, 0.05 / 3600.0);
}

TEST(ComputeSky, DefaultDeltaTIsTheCanonPolynomial) {
  const UtcTime t = UtcTime::parse("2017-08-21T18:25:32Z");
  const SkyState sky = compute_sky(kGolden, t);
  EXPECT_DOUBLE_EQ(sky.delta_t_s, delta_t_espenak_meeus(t.decimal_year()));
  EXPECT_NEAR(sky.delta_t_s, 70.3, 0.1);
}

TEST(ComputeSky, RefractionSwitch) {
  const UtcTime t = UtcTime::parse("2024-06-01T12:00:00Z");
  const SkyState with = compute_sky(kGolden, t);
  const SkyState without = compute_sky(kGolden, t, {.apply_refraction = false});
  const SolarPosition plain = solar_position(kGolden, t.julian_day(), with.delta_t_s, false);
  EXPECT_DOUBLE_EQ(without.sun.elevation_deg, plain.topocentric.true_elevation_deg);
  EXPECT_GE(with.sun.elevation_deg, without.sun.elevation_deg);
  EXPECT_GE(with.moon.elevation_deg, without.moon.elevation_deg);
}

TEST(ComputeSky, MoonIsConsistentWithItsParts) {
  const SkyState sky = compute_sky(kGolden, UtcTime::parse("2024-04-23T23:49:00Z"));  // full moon
  EXPECT_GT(sky.moon.illuminated_fraction, 0.99);
  EXPECT_LT(sky.moon.phase_angle_deg, 12.0);
  EXPECT_GT(sky.moon.illuminance_lux, 0.15);
  EXPECT_LT(sky.moon.illuminance_lux, 0.35);
  EXPECT_NEAR(sky.moon.zenith_deg, 90.0 - sky.moon.elevation_deg, 1e-12);
  // Topocentric and geocentric places differ by less than the horizontal parallax (~1 degree).
  EXPECT_LT(angular_separation_deg({sky.moon.ra_deg, sky.moon.dec_deg},
                                   {sky.moon.topocentric_ra_deg, sky.moon.topocentric_dec_deg}),
            1.0);
  EXPECT_GT(sky.moon.angular_radius_deg, 0.24);
  EXPECT_LT(sky.moon.angular_radius_deg, 0.29);
}

TEST(ComputeSky, SunDirectionInEastNorthUp) {
  const SkyState sky = compute_sky(kGolden, UtcTime::parse("2003-10-17T12:30:30-07:00"));
  const auto d = enu_direction(sky.sun.azimuth_deg, sky.sun.elevation_deg);
  // Azimuth 194 degrees: a little west of due south, up 40 degrees.
  EXPECT_LT(d[0], 0.0);
  EXPECT_LT(d[1], -0.7);
  EXPECT_NEAR(d[2], std::sin(sky.sun.elevation_deg * kDegToRad), 1e-15);
}

TEST(ComputeSky, BadInputIsAnErrorNeverClamped) {
  const UtcTime t = UtcTime::parse("2024-01-01T00:00:00Z");
  Observer o = kGolden;
  o.latitude_deg = 90.0001;
  EXPECT_NE(error_of(o, t).find("latitude"), std::string::npos);
  o.latitude_deg = std::nan("");
  EXPECT_NE(error_of(o, t).find("latitude NaN"), std::string::npos);
  o = kGolden;
  o.longitude_deg = -180.5;
  EXPECT_NE(error_of(o, t).find("longitude"), std::string::npos);
  o = kGolden;
  o.elevation_m = INFINITY;
  EXPECT_NE(error_of(o, t).find("elevation"), std::string::npos);
  o = kGolden;
  o.pressure_mbar = -1.0;
  EXPECT_NE(error_of(o, t).find("pressure"), std::string::npos);
  o = kGolden;
  o.temperature_c = -300.0;
  EXPECT_NE(error_of(o, t).find("temperature"), std::string::npos);
  EXPECT_NE(error_of(kGolden, t, {.delta_t_s = std::nan("")}).find("Delta-T"), std::string::npos);
  EXPECT_NE(error_of(kGolden, t, {.limb_darkening_u = 2.0}).find("limb"), std::string::npos);
}

TEST(ComputeSky, YearsOutsideTheAlgorithmsAreErrors) {
  // Beyond the Delta-T canon the default Delta-T is refused; an explicit one extends to SPA's
  // -2000..6000, beyond which nothing is computed.
  const UtcTime y3500 = UtcTime::from_civil(3500, 6, 1);
  EXPECT_NE(error_of(kGolden, y3500).find("Delta-T"), std::string::npos);
  EXPECT_NO_THROW(compute_sky(kGolden, y3500, {.delta_t_s = 5000.0}));
  const UtcTime y6001 = UtcTime::from_civil(6001, 1, 1);
  EXPECT_NE(error_of(kGolden, y6001, {.delta_t_s = 0.0}).find("-2000..6000"), std::string::npos);
  const UtcTime y_minus_2001 = UtcTime::from_civil(-2001, 1, 1);
  EXPECT_NE(error_of(kGolden, y_minus_2001, {.delta_t_s = 0.0}).find("-2000..6000"),
            std::string::npos);
}

TEST(ComputeSky, ExtremeObserversStayFiniteAndBounded) {
  const Observer observers[] = {
      {.latitude_deg = 90.0, .longitude_deg = 180.0},
      {.latitude_deg = -90.0, .longitude_deg = -180.0},
      {.latitude_deg = 0.0, .longitude_deg = 0.0, .elevation_m = -11000.0},
      {.latitude_deg = 45.0, .longitude_deg = 7.0, .elevation_m = 1.0e8, .pressure_mbar = 0.0},
      {.latitude_deg = 60.0,
       .longitude_deg = 25.0,
       .pressure_mbar = 2000.0,
       .temperature_c = -100.0},
  };
  for (const Observer& o : observers) {
    for (double hours = 0.0; hours < 24.0 * 30; hours += 7.3) {
      const SkyState s =
          compute_sky(o, UtcTime::parse("2024-03-01T00:00:00Z").plus_seconds(hours * 3600.0));
      for (double v :
           {s.sun.zenith_deg, s.sun.azimuth_deg, s.sun.elevation_deg, s.sun.illuminance_lux,
            s.moon.azimuth_deg, s.moon.elevation_deg, s.moon.illuminance_lux,
            s.moon.angular_radius_deg, s.sun_visible_fraction, s.sun_visible_flux_fraction}) {
        ASSERT_TRUE(std::isfinite(v)) << o.latitude_deg << " " << hours;
      }
      EXPECT_GE(s.sun.azimuth_deg, 0.0);
      EXPECT_LT(s.sun.azimuth_deg, 360.0);
      EXPECT_GE(s.moon.azimuth_deg, 0.0);
      EXPECT_LT(s.moon.azimuth_deg, 360.0);
      EXPECT_LE(std::abs(s.sun.elevation_deg), 91.0);
      EXPECT_LE(std::abs(s.moon.elevation_deg), 91.0);
      EXPECT_GE(s.sun_visible_fraction, 0.0);
      EXPECT_LE(s.sun_visible_fraction, 1.0);
      EXPECT_GE(s.moon.illuminated_fraction, 0.0);
      EXPECT_LE(s.moon.illuminated_fraction, 1.0);
    }
  }
}

TEST(ComputeSky, WholeSupportedRangeRuns) {
  for (std::int64_t year = -1999; year <= 3000; year += 111) {
    const SkyState s = compute_sky(kGolden, UtcTime::from_civil(year, 7, 1, 12));
    EXPECT_TRUE(std::isfinite(s.sun.elevation_deg)) << year;
    EXPECT_TRUE(std::isfinite(s.moon.elevation_deg)) << year;
  }
}

}  // namespace
}  // namespace welkin::timeofday
