// The METAR decoder against the published format's decoded examples: the FAA's key to METAR
// (AIM 7-1-30, station KABC), the NWS key card (KPIT) and ICAO Annex 3's example (YUDO, WMO-No. 306
// FM 15 form), then each malformed group's one error, and the bounds.
#include <gtest/gtest.h>

#include "welkin/core/error.h"
#include "welkin/weather/metar.h"

namespace {

using namespace welkin;
using namespace welkin::weather;

TEST(MetarParser, FaaKeyExample) {
  // AIM 7-1-30's example, decoded in its key: automated; wind 210 at 16 gusting 24 knots, varying
  // 180-240; 1 mile; RVR runway 11 above 6000 ft; light rain, mist; ceiling broken 1500, overcast
  // 2500; 6/4 C; altimeter 29.90. Its remarks hold groups of no body form ("3/4V1"): skipped.
  MetarReport r = parse_metar(
      "METAR KABC 121755Z AUTO 21016G24KT 180V240 1SM R11/P6000FT -RA BR BKN015 OVC025 06/04 A2990 RMK AO2 "
      "PK "
      "WND 20032/25 WSHFT 1715 VIS 3/4V1 1/2 VIS 3/4 RWY11 RAB07 CIG 013V017 CIG 017 RWY11 PRESFR SLP125 "
      "P0003 "
      "60009 T00640036 10066 21012 58033 TSNO $");
  EXPECT_EQ(r.type, "METAR");
  EXPECT_EQ(r.station, "KABC");
  EXPECT_EQ(r.day, 12);
  EXPECT_EQ(r.hour, 17);
  EXPECT_EQ(r.minute, 55);
  EXPECT_TRUE(r.automatic);
  ASSERT_TRUE(r.wind);
  EXPECT_EQ(r.wind->direction_deg, 210);
  EXPECT_DOUBLE_EQ(r.wind->speed_mps, 16 * 1852.0 / 3600.0);
  EXPECT_DOUBLE_EQ(*r.wind->gust_mps, 24 * 1852.0 / 3600.0);
  EXPECT_EQ(r.wind->variable_from_deg, 180);
  EXPECT_EQ(r.wind->variable_to_deg, 240);
  ASSERT_TRUE(r.visibility);
  EXPECT_DOUBLE_EQ(r.visibility->metres, 1609.344);
  EXPECT_TRUE(r.visibility->statute_miles);
  EXPECT_EQ(r.runway_visual_ranges, 1);
  ASSERT_EQ(r.weather.size(), 2u);
  EXPECT_EQ(r.weather[0].intensity, "-");
  EXPECT_EQ(r.weather[0].phenomena, std::vector<std::string>{"RA"});
  EXPECT_EQ(r.weather[1].phenomena, std::vector<std::string>{"BR"});
  ASSERT_EQ(r.clouds.size(), 2u);
  EXPECT_EQ(r.clouds[0].cover, CloudCover::broken);
  EXPECT_EQ(r.clouds[0].base_ft, 1500);
  EXPECT_EQ(r.clouds[1].cover, CloudCover::overcast);
  EXPECT_EQ(r.clouds[1].base_ft, 2500);
  EXPECT_EQ(r.temperature_c, 6);
  EXPECT_EQ(r.dew_point_c, 4);
  EXPECT_DOUBLE_EQ(*r.altimeter_inhg, 29.90);
  EXPECT_NEAR(*r.altimeter_hpa, 1012.5, 0.05);  // 29.90 inHg = 1012.53 hPa
}

TEST(MetarParser, NwsKeyCardExample) {
  // Corrected report; wind 220 at 15 gusting 25; 3/4 mile; RVR 28L 2600 ft; thunderstorm with
  // moderate rain; overcast cumulonimbus at 1000 ft; 18/16 C; 29.92 inHg.
  MetarReport r = parse_metar(
      "METAR KPIT 091955Z COR 22015G25KT 3/4SM R28L/2600FT TSRA OVC010CB 18/16 A2992 RMK SLP045 T01820159");
  EXPECT_TRUE(r.corrected);
  EXPECT_DOUBLE_EQ(r.visibility->metres, 0.75 * 1609.344);
  ASSERT_EQ(r.weather.size(), 1u);
  EXPECT_EQ(r.weather[0].descriptor, "TS");
  EXPECT_EQ(r.weather[0].phenomena, std::vector<std::string>{"RA"});
  ASSERT_EQ(r.clouds.size(), 1u);
  EXPECT_EQ(r.clouds[0].type, "CB");
  EXPECT_EQ(r.clouds[0].base_ft, 1000);
  EXPECT_EQ(r.clouds[0].oktas_min(), 8);
}

TEST(MetarParser, IcaoAnnex3Example) {
  // Metres and hPa, an RVR with its tendency (U), drizzle and fog; the trend (BECMG ...) skipped.
  MetarReport r = parse_metar(
      "METAR YUDO 221630Z 24015KT 0600 R12/1000U DZ FG SCT010 OVC020 17/16 Q1018 BECMG TL1700 0800 FG BECMG "
      "AT1800 9999 NSW");
  EXPECT_DOUBLE_EQ(r.visibility->metres, 600.0);
  EXPECT_FALSE(r.visibility->statute_miles);
  EXPECT_TRUE(r.has_weather("DZ"));
  EXPECT_TRUE(r.has_weather("FG"));
  EXPECT_EQ(r.clouds[0].cover, CloudCover::scattered);
  EXPECT_DOUBLE_EQ(*r.altimeter_hpa, 1018.0);
  EXPECT_FALSE(r.altimeter_inhg);
}

TEST(MetarParser, VisibilityForms) {
  auto vis = [](const std::string& group) {
    return *parse_metar("KXYZ 010000Z 00000KT " + group + " SKC 10/05 A3000").visibility;
  };
  EXPECT_DOUBLE_EQ(vis("1 1/2SM").metres, 1.5 * 1609.344);
  EXPECT_DOUBLE_EQ(vis("2 1/4SM").metres, 2.25 * 1609.344);
  EXPECT_DOUBLE_EQ(vis("5/16SM").metres, 5.0 / 16 * 1609.344);
  EXPECT_TRUE(vis("M1/4SM").less_than);
  EXPECT_TRUE(vis("P6SM").at_least);
  EXPECT_DOUBLE_EQ(vis("10SM").metres, 16093.44);
  EXPECT_TRUE(vis("9999").at_least);
  EXPECT_DOUBLE_EQ(vis("9999").metres, 10000.0);
  EXPECT_DOUBLE_EQ(vis("0800").metres, 800.0);
  MetarReport cavok = parse_metar("EGLL 271750Z VRB03KT CAVOK 12/08 Q1021");
  EXPECT_TRUE(cavok.cavok);
  EXPECT_FALSE(cavok.wind->direction_deg) << "VRB has no direction";
  EXPECT_TRUE(cavok.clouds.empty());
}

TEST(MetarParser, WindUnitsCloudsAndTemperatures) {
  MetarReport r = parse_metar("LFPG 271800Z 24008MPS 5000 -SHRA BKN014TCU VV003 M05/M10 Q1004");
  EXPECT_DOUBLE_EQ(r.wind->speed_mps, 8.0);
  EXPECT_EQ(r.weather[0].descriptor, "SH");
  EXPECT_EQ(r.clouds[0].type, "TCU");
  EXPECT_EQ(r.clouds[1].cover, CloudCover::vertical_visibility);
  EXPECT_EQ(r.clouds[1].base_ft, 300);
  EXPECT_EQ(r.temperature_c, -5);
  EXPECT_EQ(r.dew_point_c, -10);
  EXPECT_DOUBLE_EQ(parse_metar("ABCD 010000Z 09036KMH 9999 NSC 10/ Q1000").wind->speed_mps, 10.0);
  EXPECT_FALSE(parse_metar("ABCD 010000Z 09036KMH 9999 NSC 10/ Q1000").dew_point_c);
  EXPECT_EQ(parse_metar("ABCD 010000Z 00000KT 9999 NCD 10/05 Q1000=").sky_clear, "NCD");
}

// The error's `found` for a bad group: "group N 'TEXT' at column C".
std::string found_for(const std::string& report) {
  try {
    parse_metar(report);
  } catch (const Error& e) {
    return e.info().found + " | " + e.info().expected;
  }
  return "(accepted)";
}

TEST(MetarParser, EachMalformedGroupIsOneErrorNamingItAndItsPlace) {
  const std::string ok = "KSFO 271756Z 28012KT 10SM FEW008 18/12 A3001";
  struct Case {
    std::string report, found, expected_has;
  };
  const Case cases[] = {
      {"KSFO 271756Z 28012KT 10SM FEW0X8 18/12 A3001", "group 5 'FEW0X8' at column 27", "cloud group"},
      {"K1 271756Z 28012KT 10SM FEW008 18/12 A3001", "group 1 'K1' at column 1", "ICAO"},
      {"KSFO 321756Z 28012KT 10SM FEW008 18/12 A3001", "group 2 '321756Z' at column 6", "day of 01-31"},
      {"KSFO 271756Z 37012KT 10SM FEW008 18/12 A3001", "group 3 '37012KT' at column 14", "at most 360"},
      {"KSFO 271756Z 28012G10KT 10SM FEW008 18/12 A3001", "group 3 '28012G10KT' at column 14", "gust"},
      {"KSFO 271756Z 28012KT 1/3SM FEW008 18/12 A3001", "group 4 '1/3SM' at column 22", "halves, quarters"},
      {"KSFO 271756Z 28012KT 10SM FEW008 -RA 18/12 A3001", "group 6 '-RA' at column 34", "out of place"},
      {"KSFO 271756Z 28012KT 10SM FEW008 XYZ 18/12 A3001", "group 6 'XYZ' at column 34", "or a later group"},
      {"KSFO 271756Z 28012KT 10SM FEW008 12/18 A3001", "group 6 '12/18' at column 34", "dew point at most"},
      {"KSFO 271756Z 28012KT 10SM FEW008 18/12 Q0500", "group 7 'Q0500' at column 40", "850 to 1100"},
      {"KSFO 271756Z 28012KT 28012KT 10SM FEW008 18/12 A3001", "group 4 '28012KT' at column 22",
       "at most 1 of wind"},
      {"KSFO 271756Z 28012KT 10SM FEW008 SCT010 SCT020 BKN030 BKN040 OVC050 OVC060 18/12 A3001",
       "group 11 'OVC060' at column 69", "at most 6"},
      {"KSFO 271756Z 28012KT 10SM VV000 18/12 A3001", "group 5 'VV000' at column 27", "VV001"},
  };
  for (const Case& c : cases) {
    std::string got = found_for(c.report);
    EXPECT_NE(got.find(c.found), std::string::npos) << c.report << "\n  gave: " << got;
    EXPECT_NE(got.find(c.expected_has), std::string::npos) << c.report << "\n  gave: " << got;
  }
  EXPECT_EQ(found_for(ok), "(accepted)");
  EXPECT_NE(found_for("EGLL 271750Z VRB03KT CAVOK BKN010 12/08 Q1021").find("CAVOK"), std::string::npos);
  EXPECT_NE(found_for("").find("empty report"), std::string::npos);
  EXPECT_NE(found_for("KSFO").find("end of the report"), std::string::npos);
  EXPECT_NE(found_for("KSFO 271756Z 28012KT 10SM \x01 18/12").find("byte 1 at column 27"), std::string::npos);
  EXPECT_NE(found_for("KSFO 271756Z 28012KT 10SM CAF\xc3\xa9").find("byte 195"), std::string::npos);
}

TEST(MetarParser, InputBoundedBeforeParsing) {
  std::string report = "KSFO 271756Z 28012KT 10SM FEW008 18/12 A3001 RMK";
  std::string padded = report + std::string(kMaxMetarBytes - report.size(), ' ');
  EXPECT_EQ(parse_metar(padded).station, "KSFO") << "exactly the bound";
  std::string over = padded + " ";
  try {
    parse_metar(over);
    FAIL() << "a report over the bound was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.info().found, std::to_string(kMaxMetarBytes + 1) + " characters");
  }
  // A group longer than any the format has is refused by length, before any pattern sees it.
  EXPECT_NE(found_for("KSFO 271756Z " + std::string(200, '9') + "KT").find("at most 32 characters"),
            std::string::npos);
}

}  // namespace
