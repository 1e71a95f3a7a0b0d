#include "welkin/timeofday/time.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace welkin::timeofday {
namespace {

constexpr double kSecondsPerDay = 86400.0;
// Keeps day counts and Julian Days far from overflow and from losing their fraction.
constexpr std::int64_t kMaxAbsYear = 999999;
constexpr double kMaxAbsDaysFromEpoch = 1.0e9;

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

// Inverse of days_from_civil (H. Hinnant's era/day-of-era decomposition of the 400-year cycle).
CivilDateTime civil_from_days(std::int64_t days) {
  const std::int64_t z = days + 719468;
  const std::int64_t era = floor_div(z, 146097);
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  CivilDateTime out;
  out.day = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  out.month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  out.year = yoe + era * 400 + (out.month <= 2 ? 1 : 0);
  return out;
}

std::string year_month_text(std::int64_t year, int month) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%04lld-%02d", static_cast<long long>(year), month);
  return buffer;
}

// Empty when the fields are valid, else why not.
std::string check_civil(std::int64_t year, int month, int day, int hour, int minute, double second,
                        int utc_offset_minutes) {
  if (year < -kMaxAbsYear || year > kMaxAbsYear) {
    return "year " + std::to_string(year) + " is outside -999999..999999";
  }
  if (month < 1 || month > 12) return "month " + std::to_string(month) + " is outside 1-12";
  const int month_days = days_in_month(year, month);
  if (day < 1 || day > month_days) {
    return "day " + std::to_string(day) + " is outside 1-" + std::to_string(month_days) + " for " +
           year_month_text(year, month);
  }
  if (!std::isfinite(second)) return "second is not a finite number";
  if (hour == 24) {
    if (minute != 0 || second != 0.0) return "hour 24 is only allowed as 24:00:00";
  } else if (hour < 0 || hour > 23) {
    return "hour " + std::to_string(hour) + " is outside 0-23";
  }
  if (minute < 0 || minute > 59) return "minute " + std::to_string(minute) + " is outside 0-59";
  if (second < 0.0 || second >= 61.0) {
    return "second " + std::to_string(second) + " is outside [0, 61)";
  }
  if (utc_offset_minutes <= -24 * 60 || utc_offset_minutes >= 24 * 60) {
    return "UTC offset of " + std::to_string(utc_offset_minutes) + " minutes is beyond +/-23:59";
  }
  return {};
}

struct Normalized {
  std::int64_t days;
  double seconds;
};

// Empty on success; the instant lands in `out`.
std::string make_instant(std::int64_t year, int month, int day, int hour, int minute, double second,
                         int utc_offset_minutes, Normalized& out) {
  if (std::string why = check_civil(year, month, day, hour, minute, second, utc_offset_minutes);
      !why.empty()) {
    return why;
  }
  const bool leap_second = second >= 60.0;
  // A leap second is checked on the whole second before it, which must be 23:59:59 UTC.
  const double whole = leap_second ? 59.0 : second;
  std::int64_t days = days_from_civil(year, month, day);
  double seconds = hour * 3600.0 + minute * 60.0 + whole - utc_offset_minutes * 60.0;
  const double shift = std::floor(seconds / kSecondsPerDay);
  days += static_cast<std::int64_t>(shift);
  seconds -= shift * kSecondsPerDay;
  if (seconds >= kSecondsPerDay) {  // rounding of a value just below a day boundary
    seconds -= kSecondsPerDay;
    ++days;
  }
  if (leap_second) {
    if (seconds != 86399.0) return "second 60 (a leap second) is only allowed at 23:59:60 UTC";
    seconds = kSecondsPerDay + (second - 60.0);
  }
  out = {days, seconds};
  return {};
}

// A tiny cursor over the text being parsed, so each failure can say what was expected where.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  bool done() const { return pos_ >= text_.size(); }
  char peek() const { return done() ? '\0' : text_[pos_]; }
  std::size_t pos() const { return pos_; }
  void advance() { ++pos_; }

  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }

  // Reads between `min_digits` and `max_digits` decimal digits.
  bool digits(int min_digits, int max_digits, std::int64_t& value, int* count = nullptr) {
    value = 0;
    int n = 0;
    while (n < max_digits && !done() && peek() >= '0' && peek() <= '9') {
      value = value * 10 + (peek() - '0');
      ++pos_;
      ++n;
    }
    if (count != nullptr) *count = n;
    return n >= min_digits;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

std::string describe_position(const Cursor& cursor) {
  if (cursor.done()) return "at the end";
  return "at position " + std::to_string(cursor.pos() + 1) + " ('" + cursor.peek() + "')";
}

// Empty on success, else the reason (without the input, which the caller adds).
std::string parse_iso8601(std::string_view text, Normalized& out) {
  Cursor c(text);
  std::int64_t year = 0;
  int sign = 1;
  if (c.peek() == '+' || c.peek() == '-') {
    sign = c.peek() == '-' ? -1 : 1;
    c.advance();
    if (!c.digits(4, 6, year))
      return "expected a 4-6 digit year after the sign " + describe_position(c);
  } else if (!c.digits(4, 4, year)) {
    return "expected a 4-digit year " + describe_position(c);
  }
  year *= sign;
  std::int64_t month = 0, day = 0, hour = 0, minute = 0, whole_second = 0;
  if (!c.accept('-')) return "expected '-' after the year " + describe_position(c);
  if (!c.digits(2, 2, month)) return "expected a 2-digit month " + describe_position(c);
  if (!c.accept('-')) return "expected '-' after the month " + describe_position(c);
  if (!c.digits(2, 2, day)) return "expected a 2-digit day " + describe_position(c);
  if (!(c.accept('T') || c.accept('t') || c.accept(' '))) {
    return "expected 'T' and a time of day after the date " + describe_position(c);
  }
  if (!c.digits(2, 2, hour)) return "expected a 2-digit hour " + describe_position(c);
  if (!c.accept(':')) return "expected ':' after the hour " + describe_position(c);
  if (!c.digits(2, 2, minute)) return "expected a 2-digit minute " + describe_position(c);
  double second = 0.0;
  if (c.accept(':')) {
    if (!c.digits(2, 2, whole_second)) return "expected 2-digit seconds " + describe_position(c);
    second = static_cast<double>(whole_second);
    if (c.accept('.') || c.accept(',')) {
      double scale = 0.1;
      int count = 0;
      while (!c.done() && c.peek() >= '0' && c.peek() <= '9') {
        second += (c.peek() - '0') * scale;
        scale *= 0.1;
        ++count;
        c.advance();
      }
      if (count == 0) return "expected digits after the decimal mark " + describe_position(c);
    }
  }
  int offset_minutes = 0;
  if (c.accept('Z') || c.accept('z')) {
    offset_minutes = 0;
  } else if (c.peek() == '+' || c.peek() == '-') {
    const int offset_sign = c.peek() == '-' ? -1 : 1;
    c.advance();
    std::int64_t oh = 0, om = 0;
    if (!c.digits(2, 2, oh)) return "expected a 2-digit UTC offset hour " + describe_position(c);
    const bool colon = c.accept(':');
    if (colon || (!c.done() && c.peek() >= '0' && c.peek() <= '9')) {
      if (!c.digits(2, 2, om)) return "expected 2-digit UTC offset minutes " + describe_position(c);
    }
    if (oh > 23 || om > 59) return "UTC offset hours must be 00-23 and minutes 00-59";
    offset_minutes = offset_sign * static_cast<int>(oh * 60 + om);
  } else if (c.done()) {
    return "missing UTC offset: add 'Z' for UTC or an offset such as '+02:00'";
  } else {
    return "expected 'Z' or a UTC offset such as '+02:00' " + describe_position(c);
  }
  if (!c.done()) return "unexpected trailing text " + describe_position(c);
  return make_instant(year, static_cast<int>(month), static_cast<int>(day), static_cast<int>(hour),
                      static_cast<int>(minute), second, offset_minutes, out);
}

}  // namespace

bool is_leap_year(std::int64_t year) {
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int days_in_month(std::int64_t year, int month) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) {
    throw std::invalid_argument("month " + std::to_string(month) + " is outside 1-12");
  }
  return month == 2 && is_leap_year(year) ? 29 : kDays[month - 1];
}

std::int64_t days_from_civil(std::int64_t year, int month, int day) {
  const std::int64_t y = year - (month <= 2 ? 1 : 0);
  const std::int64_t era = floor_div(y, 400);
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (month + (month > 2 ? -3 : 9)) + 2) / 5 + day - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

double julian_day(std::int64_t year, int month, double day, Calendar calendar) {
  if (month < 1 || month > 12) {
    throw std::invalid_argument("julian_day: month " + std::to_string(month) + " is outside 1-12");
  }
  if (!std::isfinite(day)) throw std::invalid_argument("julian_day: day is not finite");
  double y = static_cast<double>(year);
  double m = month;
  if (month <= 2) {
    y -= 1.0;
    m += 12.0;
  }
  double b = 0.0;
  if (calendar == Calendar::kGregorian) {
    // floor rather than truncation keeps the century rule right for negative years.
    const double a = std::floor(y / 100.0);
    b = 2.0 - a + std::floor(a / 4.0);
  }
  return std::floor(365.25 * (y + 4716.0)) + std::floor(30.6001 * (m + 1.0)) + day + b - 1524.5;
}

double julian_ephemeris_day(double julian_day_ut, double delta_t_s) {
  return julian_day_ut + delta_t_s / kSecondsPerDay;
}

double julian_century(double julian_day) {
  return (julian_day - kJ2000JulianDay) / kDaysPerJulianCentury;
}

UtcTime UtcTime::from_civil(std::int64_t year, int month, int day, int hour, int minute,
                            double second, int utc_offset_minutes) {
  Normalized n{};
  if (std::string why = make_instant(year, month, day, hour, minute, second, utc_offset_minutes, n);
      !why.empty()) {
    throw std::invalid_argument("invalid UTC time: " + why);
  }
  return UtcTime(n.days, n.seconds);
}

std::optional<UtcTime> UtcTime::try_parse(std::string_view text, std::string* error) {
  Normalized n{};
  const std::string why = parse_iso8601(text, n);
  if (!why.empty()) {
    if (error != nullptr) {
      *error = "invalid ISO-8601 date-time \"" + std::string(text) + "\": " + why;
    }
    return std::nullopt;
  }
  return UtcTime(n.days, n.seconds);
}

UtcTime UtcTime::parse(std::string_view text) {
  std::string error;
  std::optional<UtcTime> time = try_parse(text, &error);
  if (!time) throw std::invalid_argument(error);
  return *time;
}

UtcTime UtcTime::from_julian_day(double jd) {
  if (!std::isfinite(jd)) throw std::invalid_argument("from_julian_day: Julian Day is not finite");
  const double x = jd - kUnixEpochJulianDay;
  if (std::fabs(x) > kMaxAbsDaysFromEpoch) {
    throw std::invalid_argument("from_julian_day: Julian Day " + std::to_string(jd) +
                                " is beyond the supported range");
  }
  double whole = std::floor(x);
  double seconds = (x - whole) * kSecondsPerDay;
  if (seconds >= kSecondsPerDay) {
    seconds -= kSecondsPerDay;
    whole += 1.0;
  }
  return UtcTime(static_cast<std::int64_t>(whole), seconds);
}

double UtcTime::julian_day() const {
  return kUnixEpochJulianDay + (static_cast<double>(days_) + seconds_ / kSecondsPerDay);
}

CivilDateTime UtcTime::civil() const {
  CivilDateTime out = civil_from_days(days_);
  if (seconds_ >= kSecondsPerDay) {  // inside a leap second
    out.hour = 23;
    out.minute = 59;
    out.second = 60.0 + (seconds_ - kSecondsPerDay);
    return out;
  }
  const double whole_minutes = std::floor(seconds_ / 60.0);
  out.hour = static_cast<int>(whole_minutes / 60.0);
  out.minute = static_cast<int>(whole_minutes - out.hour * 60.0);
  out.second = seconds_ - whole_minutes * 60.0;
  return out;
}

double UtcTime::decimal_year() const {
  const CivilDateTime date = civil_from_days(days_);
  const double start = static_cast<double>(days_from_civil(date.year, 1, 1));
  const double length = is_leap_year(date.year) ? 366.0 : 365.0;
  const double elapsed =
      static_cast<double>(days_) - start + std::fmin(seconds_, kSecondsPerDay) / kSecondsPerDay;
  return static_cast<double>(date.year) + elapsed / length;
}

UtcTime UtcTime::plus_seconds(double seconds) const {
  if (!std::isfinite(seconds)) throw std::invalid_argument("plus_seconds: not a finite number");
  // A leap second is folded into the next day first: uniform arithmetic has no 23:59:60.
  double total = std::fmin(seconds_, kSecondsPerDay) + seconds;
  const double shift = std::floor(total / kSecondsPerDay);
  if (std::fabs(shift + static_cast<double>(days_)) > kMaxAbsDaysFromEpoch) {
    throw std::invalid_argument("plus_seconds: result is beyond the supported range");
  }
  total -= shift * kSecondsPerDay;
  std::int64_t days = days_ + static_cast<std::int64_t>(shift);
  if (total >= kSecondsPerDay) {
    total -= kSecondsPerDay;
    ++days;
  }
  return UtcTime(days, total);
}

std::string UtcTime::to_iso8601() const {
  std::int64_t days = days_;
  long long ms = std::llround(seconds_ * 1000.0);
  // Rounding may carry into the next day: past 24:00 normally, past 23:59:60.999 in a leap second.
  const long long day_ms = seconds_ >= kSecondsPerDay ? 86401000LL : 86400000LL;
  if (ms >= day_ms) {
    ms -= day_ms;
    ++days;
  }
  const bool leap = ms >= 86400000LL;
  const CivilDateTime date = civil_from_days(days);
  int hour = 0, minute = 0, second = 0, milli = 0;
  if (leap) {
    hour = 23;
    minute = 59;
    second = 60;
    milli = static_cast<int>(ms - 86400000LL);
  } else {
    hour = static_cast<int>(ms / 3600000LL);
    minute = static_cast<int>(ms / 60000LL % 60);
    second = static_cast<int>(ms / 1000LL % 60);
    milli = static_cast<int>(ms % 1000LL);
  }
  char buffer[64];
  const char* format = date.year < 0 || date.year > 9999 ? "%+05lld-%02d-%02dT%02d:%02d:%02d.%03dZ"
                                                         : "%04lld-%02d-%02dT%02d:%02d:%02d.%03dZ";
  std::snprintf(buffer, sizeof buffer, format, static_cast<long long>(date.year), date.month,
                date.day, hour, minute, second, milli);
  return buffer;
}

}  // namespace welkin::timeofday
