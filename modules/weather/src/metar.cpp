// The METAR decoder: the report is split into groups, and each group is matched against the kinds
// the format allows from the current place on (wind, its variable sector, visibility, runway visual
// ranges, present weather, clouds, temperature, pressure), in that order.
#include "welkin/weather/metar.h"

#include <array>
#include <cmath>
#include <regex>

#include "welkin/core/error.h"

namespace welkin::weather {

namespace {

struct Group {
  std::string text;
  int number = 0;  // 1-based, as a reader counts them
  int column = 0;  // 1-based character where it starts
};

constexpr double kMetresPerStatuteMile = 1609.344;
constexpr double kMpsPerKnot = 1852.0 / 3600.0;
constexpr double kHpaPerInHg = 33.8638866667;
constexpr size_t kMaxGroupBytes = 32;

[[noreturn]] void refuse(const Group& g, const std::string& expected) {
  throw Error(ErrorInfo{.expected = expected,
                        .found = "group " + std::to_string(g.number) + " '" + g.text + "' at column " +
                                 std::to_string(g.column)});
}

std::vector<Group> split_groups(std::string_view text) {
  if (text.size() > kMaxMetarBytes)
    throw Error(ErrorInfo{.expected = "a report of at most " + std::to_string(kMaxMetarBytes) + " characters",
                          .found = std::to_string(text.size()) + " characters"});
  std::vector<Group> groups;
  for (size_t i = 0; i < text.size();) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
      continue;
    }
    size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\n' && text[i] != '\r') {
      unsigned char d = static_cast<unsigned char>(text[i]);
      if (d < 0x21 || d > 0x7e)
        throw Error(
            ErrorInfo{.expected = "printable ASCII characters",
                      .found = "byte " + std::to_string(int(d)) + " at column " + std::to_string(i + 1)});
      ++i;
    }
    Group g{std::string(text.substr(start, i - start)), int(groups.size()) + 1, int(start) + 1};
    if (g.text.size() > kMaxGroupBytes) refuse(g, "a group of at most 32 characters");
    groups.push_back(std::move(g));
  }
  // The end-of-message sign of WMO's bulletins.
  if (!groups.empty() && groups.back().text.size() > 1 && groups.back().text.back() == '=')
    groups.back().text.pop_back();
  return groups;
}

bool matches(const std::string& s, const char* pattern, std::smatch& m) {
  return std::regex_match(s, m, std::regex(pattern));
}

int to_int(const std::string& digits) {
  return std::stoi(digits);
}

// M12 is -12 degrees.
int signed_temperature(const std::string& t) {
  return t[0] == 'M' ? -to_int(t.substr(1)) : to_int(t);
}

// The kinds of groups, in the order the report gives them.
enum Kind {
  kWind,
  kWindSector,
  kVisibility,
  kRunwayRange,
  kWeather,
  kCloud,
  kTemperature,
  kPressure,
  kKinds
};
constexpr std::array<const char*, kKinds> kKindNames = {
    "wind (dddff[Gff]KT, VRBffKT, or in MPS or KMH)",
    "a variable wind sector (dddVddd)",
    "visibility (dddd metres, CAVOK, or statute miles: 10SM, 1/2SM, 1 1/2SM, M1/4SM, P6SM)",
    "a runway visual range (Rdd/dddd)",
    "present weather (intensity - + VC, descriptor MI BC PR DR BL SH TS FZ, phenomena such as RA SN BR FG "
    "HZ)",
    "a cloud group (FEW, SCT, BKN or OVC and three digits of hundreds of feet, then CB or TCU; VVddd; SKC, "
    "CLR, "
    "NSC or NCD)",
    "temperature and dew point (TT/DD, M for minus)",
    "the altimeter setting (Adddd in hundredths of inHg, or Qdddd in hPa)"};
// How many groups of a kind a report may hold.
constexpr std::array<int, kKinds> kMostOfKind = {1, 1, 1, 4, 3, 6, 1, 2};

std::optional<MetarWind> wind_group(const std::string& s, const Group& g) {
  std::smatch m;
  if (!matches(s, R"((\d{3}|VRB)(\d{2,3})(?:G(\d{2,3}))?(KT|MPS|KMH))", m)) return std::nullopt;
  MetarWind w;
  w.unit = m[4];
  double to_mps = w.unit == "KT" ? kMpsPerKnot : w.unit == "MPS" ? 1.0 : 1.0 / 3.6;
  if (m[1] != "VRB") {
    w.direction_deg = to_int(m[1]);
    if (*w.direction_deg > 360) refuse(g, "a wind direction of at most 360 degrees");
  }
  w.speed_as_reported = to_int(m[2]);
  w.speed_mps = w.speed_as_reported * to_mps;
  if (m[3].matched) {
    int gust = to_int(m[3]);
    if (gust <= w.speed_as_reported) refuse(g, "a gust (after G) above the mean wind");
    w.gust_mps = gust * to_mps;
  }
  return w;
}

bool wind_sector_group(const std::string& s, const Group& g, MetarWind& w) {
  std::smatch m;
  if (!matches(s, R"((\d{3})V(\d{3}))", m)) return false;
  int a = to_int(m[1]), b = to_int(m[2]);
  if (a > 360 || b > 360 || a == b)
    refuse(g, "a variable wind sector between two different directions up to 360");
  w.variable_from_deg = a;
  w.variable_to_deg = b;
  return true;
}

// Statute miles: "10", "1/2", "1 1/2" (whole part from the group before).
std::optional<double> statute_miles(const std::string& whole, const std::string& fraction, const Group& g) {
  double miles = whole.empty() ? 0.0 : to_int(whole);
  if (!fraction.empty()) {
    size_t slash = fraction.find('/');
    int num = to_int(fraction.substr(0, slash)), den = to_int(fraction.substr(slash + 1));
    if (den != 2 && den != 4 && den != 8 && den != 16)
      refuse(g, "a fraction of a mile in halves, quarters, eighths or sixteenths");
    if (num <= 0 || num >= den) refuse(g, "a proper fraction of a mile (1/4, 3/4, 5/16)");
    miles += double(num) / den;
  }
  return miles;
}

std::optional<MetarVisibility> visibility_group(const std::string& s, const Group& g) {
  std::smatch m;
  MetarVisibility v;
  if (matches(s, R"((\d{4})(NDV)?)", m)) {
    v.metres = to_int(m[1]);
    v.at_least = v.metres >= 9999;
    if (v.at_least) v.metres = 10000;
    return v;
  }
  if (matches(s, R"(([MP])?(?:(\d{1,2})|(\d{1,2}/\d{1,2}))SM)", m)) {
    v.statute_miles = true;
    v.less_than = m[1] == "M";
    v.at_least = m[1] == "P";
    v.metres = *statute_miles(m[2], m[3], g) * kMetresPerStatuteMile;
    if (v.metres <= 0.0 && !v.less_than) refuse(g, "a visibility above zero miles");
    return v;
  }
  return std::nullopt;
}

bool runway_range_group(const std::string& s) {
  std::smatch m;
  return matches(s, R"(R\d{2}[LCR]?/[PM]?\d{4}(V[PM]?\d{4})?(FT)?/?[UDN]?)", m);
}

std::optional<MetarWeather> weather_group(const std::string& s) {
  std::smatch m;
  static const char* phenomenon = "DZ|RA|SN|SG|IC|PL|GR|GS|UP|BR|FG|FU|VA|DU|SA|HZ|PY|PO|SQ|FC|SS|DS";
  std::string pattern = std::string(R"((-|\+|VC)?(MI|BC|PR|DR|BL|SH|TS|FZ)?((?:)") + phenomenon + ")*)";
  if (!matches(s, pattern.c_str(), m)) return std::nullopt;
  MetarWeather w{.intensity = m[1], .descriptor = m[2], .text = s};
  std::string all = m[3];
  for (size_t i = 0; i + 1 < all.size(); i += 2) w.phenomena.push_back(all.substr(i, 2));
  // A descriptor alone is a thunderstorm (TS) or, near the station, showers (VCSH); nothing else.
  if (w.phenomena.empty() && w.descriptor != "TS" && !(w.intensity == "VC" && w.descriptor == "SH"))
    return std::nullopt;
  return w;
}

std::optional<MetarCloud> cloud_group(const std::string& s, const Group& g) {
  std::smatch m;
  if (matches(s, R"((FEW|SCT|BKN|OVC)(\d{3})(CB|TCU)?)", m)) {
    static constexpr std::pair<const char*, CloudCover> kCovers[] = {{"FEW", CloudCover::few},
                                                                     {"SCT", CloudCover::scattered},
                                                                     {"BKN", CloudCover::broken},
                                                                     {"OVC", CloudCover::overcast}};
    MetarCloud c;
    for (auto& [code, cover] : kCovers)
      if (m[1] == code) c.cover = cover;
    c.base_ft = to_int(m[2]) * 100;
    c.type = m[3];
    return c;
  }
  if (matches(s, R"(VV(\d{3}))", m)) {
    if (to_int(m[1]) == 0) refuse(g, "a vertical visibility of at least 100 ft (VV001)");
    return MetarCloud{.cover = CloudCover::vertical_visibility, .base_ft = to_int(m[1]) * 100};
  }
  return std::nullopt;
}

bool is_sky_clear(const std::string& s) {
  return s == "SKC" || s == "CLR" || s == "NSC" || s == "NCD";
}

// Reads one group of `kind` into the report; false when the group is not of that kind.
bool read_group(Kind kind, const std::vector<Group>& groups, size_t& i, MetarReport& r) {
  const Group& g = groups[i];
  const std::string& s = g.text;
  std::smatch m;
  switch (kind) {
    case kWind:
      if (auto w = wind_group(s, g)) return r.wind = *w, true;
      return false;
    case kWindSector:
      return r.wind && wind_sector_group(s, g, *r.wind);
    case kVisibility:
      if (s == "CAVOK") {
        r.cavok = true;
        r.visibility = MetarVisibility{.metres = 10000.0, .at_least = true};
        return true;
      }
      // "1 1/2SM": a whole number of miles, then its fraction.
      if (matches(s, R"(\d)", m) && i + 1 < groups.size() &&
          matches(groups[i + 1].text, R"(\d/\d{1,2}SM)", m)) {
        MetarVisibility v{.statute_miles = true};
        v.metres =
            *statute_miles(s, groups[i + 1].text.substr(0, groups[i + 1].text.size() - 2), groups[i + 1]) *
            kMetresPerStatuteMile;
        r.visibility = v;
        ++i;
        return true;
      }
      if (auto v = visibility_group(s, g)) return r.visibility = *v, true;
      return false;
    case kRunwayRange:
      if (!runway_range_group(s)) return false;
      ++r.runway_visual_ranges;
      return true;
    case kWeather:
      if (auto w = weather_group(s)) return r.weather.push_back(*w), true;
      return false;
    case kCloud:
      if (is_sky_clear(s)) return r.sky_clear = s, true;
      if (auto c = cloud_group(s, g)) return r.clouds.push_back(*c), true;
      return false;
    case kTemperature:
      if (!matches(s, R"((M?\d{2})/(M?\d{2})?)", m)) return false;
      r.temperature_c = signed_temperature(m[1]);
      if (m[2].matched) r.dew_point_c = signed_temperature(m[2]);
      if (r.dew_point_c && *r.dew_point_c > *r.temperature_c)
        refuse(g, "a dew point at most the temperature");
      return true;
    case kPressure:
      if (matches(s, R"(A(\d{4}))", m)) {
        r.altimeter_inhg = to_int(m[1]) / 100.0;
        if (*r.altimeter_inhg < 25.0 || *r.altimeter_inhg > 35.0)
          refuse(g, "an altimeter setting of 25.00 to 35.00 inHg");
        if (!r.altimeter_hpa) r.altimeter_hpa = *r.altimeter_inhg * kHpaPerInHg;
        return true;
      }
      if (matches(s, R"(Q(\d{4}))", m)) {
        r.altimeter_hpa = to_int(m[1]);
        if (*r.altimeter_hpa < 850 || *r.altimeter_hpa > 1100) refuse(g, "a QNH of 850 to 1100 hPa");
        return true;
      }
      return false;
    case kKinds:
      break;
  }
  return false;
}

// What a malformed group was most likely meant to be, for the error.
Kind meant_kind(const std::string& s, Kind next) {
  auto ends = [&](std::string_view e) {
    return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
  };
  auto starts = [&](std::string_view b) { return s.rfind(b, 0) == 0; };
  if (ends("KT") || ends("MPS") || ends("KMH")) return kWind;
  if (ends("SM")) return kVisibility;
  if (starts("FEW") || starts("SCT") || starts("BKN") || starts("OVC") || starts("VV")) return kCloud;
  if (s.find('/') != std::string::npos && starts("R") && s.size() > 3) return kRunwayRange;
  if (s.find('/') != std::string::npos) return kTemperature;
  if ((starts("A") || starts("Q")) && s.size() == 5) return kPressure;
  return next;
}

void read_header(const std::vector<Group>& groups, size_t& i, MetarReport& r) {
  std::smatch m;
  if (i < groups.size() && (groups[i].text == "METAR" || groups[i].text == "SPECI"))
    r.type = groups[i++].text;
  if (i >= groups.size())
    throw Error(ErrorInfo{.expected = "a station (four letters, e.g. KSFO)", .found = "an empty report"});
  if (!matches(groups[i].text, R"([A-Z][A-Z0-9]{3})", m))
    refuse(groups[i], "the station's ICAO indicator (four letters, e.g. KSFO)");
  r.station = groups[i++].text;
  if (i >= groups.size())
    throw Error(ErrorInfo{.expected = "the day and time (ddhhmmZ) after " + r.station,
                          .found = "the end of the report"});
  if (!matches(groups[i].text, R"((\d{2})(\d{2})(\d{2})Z)", m))
    refuse(groups[i], "the day and UTC time (ddhhmmZ, e.g. 271756Z)");
  r.day = to_int(m[1]), r.hour = to_int(m[2]), r.minute = to_int(m[3]);
  if (r.day < 1 || r.day > 31 || r.hour > 23 || r.minute > 59)
    refuse(groups[i], "a day of 01-31, an hour of 00-23 and a minute of 00-59");
  ++i;
  for (; i < groups.size() && (groups[i].text == "AUTO" || groups[i].text == "COR"); ++i)
    (groups[i].text == "AUTO" ? r.automatic : r.corrected) = true;
}

}  // namespace

bool MetarWeather::has(std::string_view p) const {
  for (const auto& x : phenomena)
    if (x == p) return true;
  return false;
}

bool MetarReport::has_weather(std::string_view p) const {
  for (const auto& w : weather)
    if (w.has(p)) return true;
  return false;
}

int MetarCloud::oktas_min() const {
  constexpr int kMin[] = {1, 3, 5, 8, 8};
  return kMin[int(cover)];
}
int MetarCloud::oktas_max() const {
  constexpr int kMax[] = {2, 4, 7, 8, 8};
  return kMax[int(cover)];
}

const char* cover_code(CloudCover cover) {
  constexpr const char* kCodes[] = {"FEW", "SCT", "BKN", "OVC", "VV"};
  return kCodes[int(cover)];
}

MetarReport parse_metar(std::string_view text) {
  std::vector<Group> groups = split_groups(text);
  MetarReport r;
  size_t i = 0;
  read_header(groups, i, r);
  std::array<int, kKinds> seen{};
  int next = kWind;  // the first kind still allowed
  for (; i < groups.size(); ++i) {
    const Group& g = groups[i];
    if (g.text == "RMK" || g.text == "NOSIG" || g.text == "BECMG" || g.text == "TEMPO") break;
    bool read = false;
    for (int k = next; k < kKinds && !read; ++k) {
      if (!read_group(Kind(k), groups, i, r)) continue;
      read = true;
      if (++seen[k] > kMostOfKind[k])
        refuse(g, "at most " + std::to_string(kMostOfKind[k]) + " of " + kKindNames[k]);
      next = k;
    }
    if (read) continue;
    MetarReport scratch = r;
    size_t j = i;
    for (int k = 0; k < next; ++k)
      if (read_group(Kind(k), groups, j, scratch))
        refuse(g, std::string(kKindNames[next]) + " or a later group (this " + kKindNames[k] +
                      " is out of place)");
    Kind meant = meant_kind(g.text, Kind(next));
    refuse(g, meant == next ? std::string(kKindNames[next]) + " or a later group" : kKindNames[meant]);
  }
  if (r.cavok && (!r.weather.empty() || !r.clouds.empty()))
    throw Error(ErrorInfo{.expected = "no weather or cloud groups with CAVOK", .found = "CAVOK with them"});
  return r;
}

}  // namespace welkin::weather
