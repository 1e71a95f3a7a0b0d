// Calendar arithmetic, Julian Day and a UTC instant type with ISO-8601 parsing.
//
// Dates are proleptic Gregorian with astronomical year numbering (year 0 = 1 BC), as ISO 8601
// prescribes; the Julian calendar is only offered for reproducing historical worked examples.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace welkin::timeofday {

// Julian Day of the J2000.0 epoch (2000-01-01 12:00 TT).
inline constexpr double kJ2000JulianDay = 2451545.0;
// Days in a Julian century, the time unit of every series in this library.
inline constexpr double kDaysPerJulianCentury = 36525.0;
// Julian Day of the Unix epoch, 1970-01-01T00:00:00Z.
inline constexpr double kUnixEpochJulianDay = 2440587.5;

// Which calendar a (year, month, day) triple is written in.
enum class Calendar { kGregorian, kJulian };

// True for Gregorian leap years: divisible by 4, except centuries not divisible by 400.
bool is_leap_year(std::int64_t year);

// Days in `month` (1-12) of `year`, Gregorian. Throws std::invalid_argument for a bad month.
int days_in_month(std::int64_t year, int month);

// Julian Day of a calendar date whose `day` may carry a fraction (Meeus, Astronomical Algorithms,
// eq. 7.1). Throws std::invalid_argument for a month outside 1-12 or a non-finite day.
double julian_day(std::int64_t year, int month, double day,
                  Calendar calendar = Calendar::kGregorian);

// Julian Ephemeris Day (TT) from a Julian Day in UT and Delta-T = TT - UT in seconds.
double julian_ephemeris_day(double julian_day_ut, double delta_t_s);

// Julian centuries since J2000.0 for a Julian (Ephemeris) Day.
double julian_century(double julian_day);

// Broken-down civil date and time; `second` carries the fraction and may reach 60 in a leap second.
struct CivilDateTime {
  std::int64_t year = 2000;
  int month = 1;
  int day = 1;
  int hour = 0;
  int minute = 0;
  double second = 0.0;
};

// An instant in UTC, stored as whole days since 1970-01-01 plus seconds into that day. Always
// valid: every way to make one checks its input. Leap seconds (23:59:60) are accepted and, since
// Julian Days count uniform days, map onto the first second of the next day in julian_day().
class UtcTime {
 public:
  // 2000-01-01T00:00:00Z.
  UtcTime() = default;

  // Builds an instant from civil fields given in local time `utc_offset_minutes` ahead of UTC
  // (e.g. -420 for UTC-7). Throws std::invalid_argument naming the first bad field.
  static UtcTime from_civil(std::int64_t year, int month, int day, int hour = 0, int minute = 0,
                            double second = 0.0, int utc_offset_minutes = 0);

  // Parses ISO-8601 / RFC-3339 date-times: `YYYY-MM-DDThh:mm[:ss[.fff]]` followed by `Z` or an
  // offset `+/-hh[:mm]`. A missing offset is an error, since local time is ambiguous. Returns
  // nullopt and, when `error` is given, a message naming the offending part and the input.
  static std::optional<UtcTime> try_parse(std::string_view text, std::string* error = nullptr);

  // As try_parse, but throws std::invalid_argument carrying the message.
  static UtcTime parse(std::string_view text);

  // The instant of a Julian Day (UT). Throws std::invalid_argument if `jd` is not finite or lies
  // beyond about +/-2.7 million years.
  static UtcTime from_julian_day(double jd);

  // Julian Day (UT) of this instant.
  double julian_day() const;

  // Civil fields of this instant in UTC.
  CivilDateTime civil() const;

  // Calendar year, used to pick Delta-T and to check an algorithm's supported range.
  std::int64_t year() const { return civil().year; }

  // Fractional year, e.g. 2024.5 near July 2; what Delta-T polynomials take.
  double decimal_year() const;

  // The instant `seconds` later (earlier if negative). Throws std::invalid_argument if not finite.
  UtcTime plus_seconds(double seconds) const;

  // ISO-8601 text with millisecond precision, e.g. `2003-10-17T19:30:30.000Z`.
  std::string to_iso8601() const;

  // Days since 1970-01-01 (negative before).
  std::int64_t days_since_unix_epoch() const { return days_; }

  // Seconds into the UTC day, in [0, 86401) (a leap second reaches past 86400).
  double seconds_of_day() const { return seconds_; }

  friend auto operator<=>(const UtcTime&, const UtcTime&) = default;

 private:
  UtcTime(std::int64_t days, double seconds) : days_(days), seconds_(seconds) {}

  std::int64_t days_ = 10957;  // 2000-01-01
  double seconds_ = 0.0;
};

// Days since 1970-01-01 of a proleptic Gregorian date; fields are not checked.
std::int64_t days_from_civil(std::int64_t year, int month, int day);

}  // namespace welkin::timeofday
