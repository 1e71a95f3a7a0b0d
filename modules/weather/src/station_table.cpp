#include "welkin/weather/station_table.h"

#include <charconv>
#include <cmath>

#include "welkin/core/error.h"
#include "welkin/core/files.h"

namespace welkin::weather {

namespace {

double read_degrees(std::string_view field, double limit, const std::string& where) {
  double v = 0.0;
  auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v) || std::abs(v) > limit)
    throw Error(ErrorInfo{.path = where,
                          .expected = "degrees within +-" + std::to_string(int(limit)),
                          .found = "'" + std::string(field) + "'"});
  return v;
}

}  // namespace

std::optional<Station> find_station(const std::string& path, std::string_view icao) {
  std::string text = read_file_text(path, kMaxStationTableBytes);
  std::string_view rest(text);
  for (int line = 1; !rest.empty(); ++line) {
    size_t eol = rest.find('\n');
    std::string_view row = rest.substr(0, eol);
    rest = eol == std::string_view::npos ? std::string_view() : rest.substr(eol + 1);
    if (row.empty() || row[0] == '#') continue;
    std::string where = "line " + std::to_string(line);
    size_t c1 = row.find(','), c2 = c1 == row.npos ? c1 : row.find(',', c1 + 1),
           c3 = c2 == row.npos ? c2 : row.find(',', c2 + 1);
    if (c3 == row.npos)
      throw Error(ErrorInfo{.file = path,
                            .path = where,
                            .expected = "ICAO,latitude_deg,longitude_deg,name",
                            .found = "'" + std::string(row.substr(0, 60)) + "'"});
    if (row.substr(0, c1) != icao) continue;
    try {
      return Station{std::string(icao), read_degrees(row.substr(c1 + 1, c2 - c1 - 1), 90.0, where),
                     read_degrees(row.substr(c2 + 1, c3 - c2 - 1), 180.0, where),
                     std::string(row.substr(c3 + 1))};
    } catch (const Error& e) {
      throw e.with_file(path);
    }
  }
  return std::nullopt;
}

}  // namespace welkin::weather
