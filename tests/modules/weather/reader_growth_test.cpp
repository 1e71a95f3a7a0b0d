// The weather module's readers do work linear in their input (issue 37): a METAR report with n, 10n
// and 100n remark groups (the one part of a report whose groups have no count of their own, inside
// the report's 1 KiB bound), and the station table read for the last of n, 10n and 100n stations
// (inside its 4 MiB bound). The time may grow about 10x a step, not 100x (growth.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "growth.h"
#include "welkin/weather/metar.h"
#include "welkin/weather/station_table.h"
#include "scratch_folder.h"

namespace {

using welkin::testing::measure_growth;

std::string report_with_remarks(size_t remarks) {
  std::string r = "KSFO 271156Z 00000KT 10SM CLR 15/10 A3000 RMK";
  for (size_t i = 0; i < remarks; ++i) r += " AO2";
  return r;
}

TEST(WeatherReaderGrowth, MetarWithManyRemarks) {
  ASSERT_LE(report_with_remarks(200).size(), welkin::weather::kMaxMetarBytes);
  ASSERT_EQ(welkin::weather::parse_metar(report_with_remarks(200)).station, "KSFO");
  const auto g = measure_growth(2, report_with_remarks, [](const std::string& report) {
    for (int i = 0; i < 20; ++i) welkin::weather::parse_metar(report);  // long enough to time
  });
  EXPECT_TRUE(g.linear()) << g.describe();
}

// Four letters for i, in increasing order: AAAA, AAAB, ...
std::string icao(size_t i) {
  std::string s(4, 'A');
  for (int k = 3; k >= 0; --k, i /= 26) s[size_t(k)] = char('A' + i % 26);
  return s;
}

TEST(WeatherReaderGrowth, StationTableWithManyStations) {
  const std::filesystem::path& dir = welkin::testing::scratch_folder("welkin-weather-growth");
  auto make = [&](size_t stations) {
    const std::string path = (dir / ("stations-" + std::to_string(stations) + ".csv")).string();
    std::ofstream out(path);
    out << "# ICAO,latitude_deg,longitude_deg,name\n";
    for (size_t i = 0; i < stations; ++i) out << icao(i) << ",46.5,7.25,Station\n";
    return std::make_pair(path, icao(stations - 1));
  };
  const auto last = make(1000);
  ASSERT_LE(std::filesystem::file_size(last.first) * 100, welkin::weather::kMaxStationTableBytes);
  const auto found = welkin::weather::find_station(last.first, last.second);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->icao, last.second);
  EXPECT_DOUBLE_EQ(found->longitude_deg, 7.25);
  const auto g = measure_growth(1000, make, [](const std::pair<std::string, std::string>& table) {
    welkin::weather::find_station(table.first, table.second);
  });
  EXPECT_TRUE(g.linear()) << g.describe();
  std::filesystem::remove_all(dir);
}

}  // namespace
