// Calendar, Julian Day and ISO-8601 parsing, against Meeus (Astronomical Algorithms, 2nd ed.,
// ch. 7) and the NREL SPA report's worked example.
#include "welkin/timeofday/time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace welkin::timeofday {
namespace {

// Resolution of a double Julian Day near 2.4e6 is ~4.7e-10 day (40 microseconds).
constexpr double kJdTolerance = 1e-9;

TEST(JulianDay, MeeusExample7a) {
  // 1957 October 4.81, the launch of Sputnik 1.
  EXPECT_NEAR(julian_day(1957, 10, 4.81), 2436116.31, kJdTolerance);
}

TEST(JulianDay, MeeusExample7bJulianCalendar) {
  // 333 January 27, 12h, a date of the Julian calendar.
  EXPECT_NEAR(julian_day(333, 1, 27.5, Calendar::kJulian), 1842713.0, kJdTolerance);
}

TEST(JulianDay, MeeusChapter7TableGregorian) {
  struct Case {
    int year, month;
    double day, jd;
  };
  const Case cases[] = {
      {2000, 1, 1.5, 2451545.0},  {1999, 1, 1.0, 2451179.5},  {1987, 1, 27.0, 2446822.5},
      {1987, 6, 19.5, 2446966.0}, {1988, 1, 27.0, 2447187.5}, {1988, 6, 19.5, 2447332.0},
      {1900, 1, 1.0, 2415020.5},  {1600, 1, 1.0, 2305447.5},  {1600, 12, 31.0, 2305812.5}};
  for (const Case& c : cases) {
    EXPECT_NEAR(julian_day(c.year, c.month, c.day), c.jd, kJdTolerance)
        << c.year << "-" << c.month << "-" << c.day;
  }
}

TEST(JulianDay, MeeusChapter7TableJulianCalendar) {
  struct Case {
    int year, month;
    double day, jd;
  };
  const Case cases[] = {{837, 4, 10.3, 2026871.8},   {-123, 12, 31.0, 1676496.5},
                        {-122, 1, 1.0, 1676497.5},   {-1000, 7, 12.5, 1356001.0},
                        {-1000, 2, 29.0, 1355866.5}, {-1001, 8, 17.9, 1355671.4},
                        {-4712, 1, 1.5, 0.0}};
  for (const Case& c : cases) {
    EXPECT_NEAR(julian_day(c.year, c.month, c.day, Calendar::kJulian), c.jd, kJdTolerance)
        << c.year << "-" << c.month << "-" << c.day;
  }
}

TEST(JulianDay, UtcTimeAgreesWithMeeusFormulaAcrossEras) {
  // Two independent algorithms (Meeus' INT formula, the 400-year-era day count) must agree on
  // every proleptic Gregorian date, negative years included.
  for (std::int64_t year = -2000; year <= 6000; year += 37) {
    for (int month = 1; month <= 12; ++month) {
      const int day = days_in_month(year, month);
      const double expected = julian_day(year, month, day + 0.25);
      const double actual = UtcTime::from_civil(year, month, day, 6).julian_day();
      ASSERT_NEAR(actual, expected, kJdTolerance) << year << "-" << month << "-" << day;
    }
  }
}

TEST(UtcTime, SpaExampleJulianDay) {
  // SPA report Table A5.1: 2003-10-17 12:30:30 local time at UTC-7 is JD 2452930.312847.
  const UtcTime t = UtcTime::parse("2003-10-17T12:30:30-07:00");
  EXPECT_NEAR(t.julian_day(), 2452930.312847, 5e-7);
  EXPECT_EQ(t.to_iso8601(), "2003-10-17T19:30:30.000Z");
}

TEST(UtcTime, MeeusExample7aThroughParser) {
  EXPECT_NEAR(UtcTime::parse("1957-10-04T19:26:24Z").julian_day(), 2436116.31, kJdTolerance);
}

TEST(UtcTime, FromJulianDayMeeusExample7c) {
  // Meeus example 7.c: JD 2436116.31 is 1957 October 4.81 = 19:26:24.
  const CivilDateTime c = UtcTime::from_julian_day(2436116.31).civil();
  EXPECT_EQ(c.year, 1957);
  EXPECT_EQ(c.month, 10);
  EXPECT_EQ(c.day, 4);
  EXPECT_EQ(c.hour, 19);
  EXPECT_EQ(c.minute, 26);
  EXPECT_NEAR(c.second, 24.0, 1e-3);
}

TEST(UtcTime, JulianDayRoundTrip) {
  for (double jd = 1000000.25; jd < 4000000.0; jd += 12345.678) {
    EXPECT_NEAR(UtcTime::from_julian_day(jd).julian_day(), jd, 1e-8) << jd;
  }
}

TEST(UtcTime, LeapYears) {
  EXPECT_TRUE(is_leap_year(2000));
  EXPECT_FALSE(is_leap_year(1900));
  EXPECT_FALSE(is_leap_year(2100));
  EXPECT_TRUE(is_leap_year(2024));
  EXPECT_FALSE(is_leap_year(2023));
  EXPECT_TRUE(is_leap_year(0));  // 1 BC, astronomical numbering
  EXPECT_TRUE(UtcTime::try_parse("2000-02-29T12:00:00Z").has_value());
  EXPECT_TRUE(UtcTime::try_parse("2024-02-29T12:00:00Z").has_value());
  std::string error;
  EXPECT_FALSE(UtcTime::try_parse("1900-02-29T12:00:00Z", &error).has_value());
  EXPECT_NE(error.find("day 29 is outside 1-28 for 1900-02"), std::string::npos) << error;
  EXPECT_FALSE(UtcTime::try_parse("2100-02-29T12:00:00Z", &error).has_value());
  EXPECT_NE(error.find("2100-02"), std::string::npos) << error;
  EXPECT_THROW(UtcTime::from_civil(2100, 2, 29), std::invalid_argument);
  EXPECT_EQ(days_in_month(2024, 2), 29);
  EXPECT_EQ(days_in_month(2023, 2), 28);
  EXPECT_THROW(days_in_month(2023, 13), std::invalid_argument);
}

TEST(UtcTime, JulianDayContinuousAcrossMidnightAndYears) {
  const double before = UtcTime::parse("2023-12-31T23:59:59.999Z").julian_day();
  const double after = UtcTime::parse("2024-01-01T00:00:00Z").julian_day();
  EXPECT_NEAR(after - before, 0.001 / 86400.0, kJdTolerance);
  EXPECT_DOUBLE_EQ(after - UtcTime::parse("2023-01-01T00:00:00Z").julian_day(), 365.0);
  EXPECT_DOUBLE_EQ(UtcTime::parse("2025-01-01T00:00:00Z").julian_day() - after, 366.0);
  EXPECT_DOUBLE_EQ(UtcTime::parse("2024-03-01T00:00:00Z").julian_day() -
                       UtcTime::parse("2024-02-28T00:00:00Z").julian_day(),
                   2.0);
  // Every midnight of a leap year sits exactly one day after the previous one.
  UtcTime t = UtcTime::from_civil(2024, 1, 1);
  for (int i = 0; i < 366; ++i) {
    const UtcTime next = t.plus_seconds(86400.0);
    ASSERT_DOUBLE_EQ(next.julian_day() - t.julian_day(), 1.0);
    t = next;
  }
  EXPECT_EQ(t.to_iso8601(), "2025-01-01T00:00:00.000Z");
}

TEST(UtcTime, OffsetsNormaliseToUtc) {
  const UtcTime utc = UtcTime::parse("2003-10-17T19:30:30Z");
  EXPECT_EQ(UtcTime::parse("2003-10-17T12:30:30-07:00"), utc);
  EXPECT_EQ(UtcTime::parse("2003-10-18T01:00:30+05:30"), utc);
  EXPECT_EQ(UtcTime::parse("2003-10-18T01:00:30+0530"), utc);
  EXPECT_EQ(UtcTime::parse("2003-10-17t19:30:30z"), utc);
  EXPECT_EQ(UtcTime::parse("2003-10-17 19:30:30+00"), utc);
  EXPECT_EQ(UtcTime::from_civil(2003, 10, 17, 12, 30, 30.0, -7 * 60), utc);
  // An offset can move the date across a year boundary.
  EXPECT_EQ(UtcTime::parse("2024-01-01T01:00:00+02:00").to_iso8601(), "2023-12-31T23:00:00.000Z");
}

TEST(UtcTime, FractionalSecondsAndOptionalSeconds) {
  const UtcTime t = UtcTime::parse("2003-10-17T19:30:30.25Z");
  EXPECT_DOUBLE_EQ(t.seconds_of_day(), 19 * 3600 + 30 * 60 + 30.25);
  EXPECT_EQ(UtcTime::parse("2003-10-17T19:30:30,25Z"), t);
  EXPECT_EQ(UtcTime::parse("2003-10-17T19:30Z").to_iso8601(), "2003-10-17T19:30:00.000Z");
  EXPECT_EQ(UtcTime::parse("2003-10-17T24:00:00Z").to_iso8601(), "2003-10-18T00:00:00.000Z");
}

TEST(UtcTime, LeapSecond) {
  const UtcTime t = UtcTime::parse("2016-12-31T23:59:60.5Z");
  EXPECT_EQ(t.civil().second, 60.5);
  EXPECT_EQ(t.to_iso8601(), "2016-12-31T23:59:60.500Z");
  EXPECT_EQ(UtcTime::parse("2017-01-01T00:59:60+01:00"), UtcTime::parse("2016-12-31T23:59:60Z"));
  std::string error;
  EXPECT_FALSE(UtcTime::try_parse("2016-12-31T12:00:60Z", &error).has_value());
  EXPECT_NE(error.find("leap second"), std::string::npos) << error;
}

TEST(UtcTime, BadInputGivesClearErrors) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"", "4-digit year"},
      {"hello", "4-digit year"},
      {"2003-10-17T19:30:30", "missing UTC offset"},
      {"2003-10-17", "expected 'T'"},
      {"2003-13-01T00:00:00Z", "month 13 is outside 1-12"},
      {"2003-00-01T00:00:00Z", "month 0 is outside 1-12"},
      {"2003-04-31T00:00:00Z", "day 31 is outside 1-30"},
      {"2003-10-17T25:00:00Z", "hour 25 is outside 0-23"},
      {"2003-10-17T24:00:01Z", "hour 24 is only allowed as 24:00:00"},
      {"2003-10-17T12:60:00Z", "minute 60 is outside 0-59"},
      {"2003-10-17T12:00:61Z", "second"},
      {"2003-10-17T12:00:00.Z", "digits after the decimal mark"},
      {"2003-10-17T12:00:00+25:00", "UTC offset"},
      {"2003-10-17T12:00:00Zjunk", "trailing text"},
      {"2003/10/17T12:00:00Z", "expected '-' after the year"},
  };
  for (const Case& c : cases) {
    std::string error;
    EXPECT_FALSE(UtcTime::try_parse(c.text, &error).has_value()) << c.text;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.text << " -> " << error;
    EXPECT_NE(error.find(std::string("\"") + c.text + "\""), std::string::npos) << error;
    EXPECT_THROW(UtcTime::parse(c.text), std::invalid_argument) << c.text;
  }
  EXPECT_THROW(UtcTime::from_julian_day(std::nan("")), std::invalid_argument);
  EXPECT_THROW(UtcTime::from_civil(2024, 1, 1, 0, 0, std::nan("")), std::invalid_argument);
  EXPECT_THROW(UtcTime::parse("2024-01-01T00:00:00Z").plus_seconds(INFINITY),
               std::invalid_argument);
}

TEST(UtcTime, ExpandedAndNegativeYears) {
  const UtcTime t = UtcTime::parse("-0500-03-01T00:00:00Z");
  EXPECT_EQ(t.year(), -500);
  EXPECT_EQ(UtcTime::parse(t.to_iso8601()), t);
  EXPECT_NEAR(t.julian_day(), julian_day(-500, 3, 1.0), kJdTolerance);
}

TEST(UtcTime, DecimalYear) {
  EXPECT_DOUBLE_EQ(UtcTime::parse("2024-01-01T00:00:00Z").decimal_year(), 2024.0);
  EXPECT_NEAR(UtcTime::parse("2023-07-02T12:00:00Z").decimal_year(), 2023.5, 1e-12);
}

TEST(JulianCentury, J2000IsZero) {
  EXPECT_DOUBLE_EQ(julian_century(kJ2000JulianDay), 0.0);
  EXPECT_DOUBLE_EQ(julian_century(kJ2000JulianDay + kDaysPerJulianCentury), 1.0);
  // SPA report: JDE 2452930.313623 for Delta-T = 67 s.
  const double jd = UtcTime::parse("2003-10-17T19:30:30Z").julian_day();
  EXPECT_NEAR(julian_ephemeris_day(jd, 67.0), 2452930.313623, 5e-7);
}

}  // namespace
}  // namespace welkin::timeofday
