// The mapping from a report to the sky, against hand-worked values: the WMO's cloud étages and
// oktas, the drift of a wind from its direction, Koschmieder's law at the WMO's 5% threshold.
#include "welkin/weather/sky_from_metar.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace welkin;
using namespace welkin::weather;
using clouds::Genus;

TEST(SkyFromMetar, IssueExampleLayers) {
  SkyFromReport sky =
      sky_from_metar(parse_metar("KSFO 271756Z 28012KT 10SM FEW008 SCT025 BKN250 18/12 A3001"));
  ASSERT_EQ(sky.layers.size(), 3u);
  EXPECT_EQ(sky.layers[0].genus, Genus::cumulus);
  EXPECT_FLOAT_EQ(sky.layers[0].base_altitude_m, 800 * 0.3048f);
  EXPECT_FLOAT_EQ(sky.layers[0].coverage, coverage_parameter_for(1.5f / 8));
  EXPECT_EQ(sky.layers[1].genus, Genus::cumulus);
  EXPECT_FLOAT_EQ(sky.layers[1].coverage, coverage_parameter_for(3.5f / 8));
  EXPECT_EQ(sky.layers[2].genus, Genus::cirrus) << "BKN at 25 000 ft is a high cloud";
  EXPECT_FLOAT_EQ(sky.layers[2].coverage, coverage_parameter_for(6.0f / 8));
  EXPECT_FALSE(sky.layers[2].casts_shadow);
  EXPECT_FALSE(sky.visibility_m) << "10 miles is clear air: the scene's haze stays";
  EXPECT_EQ(sky.day, 27);
  EXPECT_DOUBLE_EQ(sky.utc_time_h, 17.0 + 56.0 / 60.0);
  // From 280 degrees at 12 knots: toward 100 degrees, mostly east, a little south.
  double v = 12 * 1852.0 / 3600.0, a = 280.0 * M_PI / 180.0;
  EXPECT_NEAR(sky.wind_mps.x, -v * std::sin(a), 1e-5);
  EXPECT_NEAR(sky.wind_mps.y, -v * std::cos(a), 1e-5);
  EXPECT_GT(sky.wind_mps.x, 6.0f);
  EXPECT_LT(sky.wind_mps.y, -1.0f);
  for (const auto& l : sky.layers) EXPECT_EQ(l.wind_mps, sky.wind_mps);
}

TEST(SkyFromMetar, CoverageFromOktasThroughTheMeasuredCurve) {
  // The oktas' middles: FEW 1-2, SCT 3-4, BKN 5-7, OVC 8.
  auto fraction = [](const char* group) {
    return sky_fraction_of(
        parse_metar(std::string("KXYZ 010000Z 00000KT 9999 ") + group + " 10/05 Q1013").clouds.at(0));
  };
  EXPECT_FLOAT_EQ(fraction("FEW030"), 1.5f / 8);
  EXPECT_FLOAT_EQ(fraction("SCT030"), 3.5f / 8);
  EXPECT_FLOAT_EQ(fraction("BKN030"), 6.0f / 8);
  EXPECT_FLOAT_EQ(fraction("OVC030"), 1.0f);
  EXPECT_FLOAT_EQ(fraction("VV003"), 1.0f);
  // Points of the measured curve come back exactly; between them it is linear and increasing.
  EXPECT_NEAR(coverage_parameter_for(0.353f), 0.45f, 1e-6);
  EXPECT_NEAR(coverage_parameter_for(0.834f), 0.75f, 1e-6);
  EXPECT_NEAR(coverage_parameter_for(1.5f / 8), 0.35f + 0.1f * (0.1875f - 0.171f) / (0.353f - 0.171f), 1e-6);
  EXPECT_EQ(coverage_parameter_for(0.0f), 0.0f);
  EXPECT_EQ(coverage_parameter_for(1.0f), 1.0f);
  float last = 0.0f;
  for (float f = 0.01f; f < 1.0f; f += 0.01f) {
    float c = coverage_parameter_for(f);
    EXPECT_GT(c, last) << f;
    last = c;
  }
}

TEST(SkyFromMetar, GenusByHeightAmountAndType) {
  auto genus = [](const std::string& cloud, const std::string& weather = "") {
    MetarReport r = parse_metar("KXYZ 010000Z 00000KT 9999 " + weather + cloud + " 10/05 Q1013");
    return genus_of(r.clouds.at(0), r);
  };
  EXPECT_EQ(genus("FEW030"), Genus::cumulus);
  EXPECT_EQ(genus("SCT045"), Genus::cumulus);
  EXPECT_EQ(genus("BKN040"), Genus::stratocumulus);
  EXPECT_EQ(genus("OVC020"), Genus::stratocumulus);
  EXPECT_EQ(genus("OVC005"), Genus::stratus);
  EXPECT_EQ(genus("OVC015", "RA "), Genus::nimbostratus);
  EXPECT_EQ(genus("SCT030TCU"), Genus::cumulus);
  EXPECT_EQ(genus("BKN025CB"), Genus::cumulonimbus);
  EXPECT_EQ(genus("SCT100"), Genus::altocumulus);
  EXPECT_EQ(genus("OVC120"), Genus::altostratus);
  EXPECT_EQ(genus("FEW250"), Genus::cirrus);
  EXPECT_EQ(genus("OVC280"), Genus::cirrostratus);
  EXPECT_EQ(genus("VV002"), Genus::stratus);
  // The étages' edges: 6500 ft is middle, 6400 low; 20 000 high.
  EXPECT_EQ(genus("SCT064"), Genus::cumulus);
  EXPECT_EQ(genus("SCT065"), Genus::altocumulus);
  EXPECT_EQ(genus("SCT200"), Genus::cirrus);
}

TEST(SkyFromMetar, ThicknessOfTowersAndObscuredSky) {
  SkyFromReport sky = sky_from_metar(parse_metar("KXYZ 010000Z 00000KT 9999 SCT030TCU BKN040CB 10/05 Q1013"));
  EXPECT_FLOAT_EQ(sky.layers[0].thickness_m, 4000.0f);
  EXPECT_FLOAT_EQ(sky.layers[1].thickness_m, 11000.0f - 4000 * 0.3048f) << "a CB reaches the tropopause";
  SkyFromReport fog = sky_from_metar(parse_metar("LSZH 271820Z 05004KT 0300 FG VV001 02/02 Q1030"));
  EXPECT_FLOAT_EQ(fog.layers[0].base_altitude_m, 0.0f);
  EXPECT_FLOAT_EQ(fog.layers[0].coverage, 1.0f);
  ASSERT_TRUE(fog.visibility_m);
  EXPECT_DOUBLE_EQ(*fog.visibility_m, 300.0);
}

TEST(SkyFromMetar, VisibilityIsKoschmiedersRange) {
  // At the visibility, the contrast of a black object against the horizon falls to 5%:
  // exp(-(aerosol + air) V) = 0.05.
  const double rayleigh = 13.558e-3;
  for (double v : {300.0, 1000.0, 4800.0, 9000.0}) {
    double total = haze_extinction_per_km(v, rayleigh) + rayleigh;
    EXPECT_NEAR(std::exp(-total * v / 1000.0), 0.05, 1e-12) << v;
  }
  EXPECT_EQ(haze_extinction_per_km(1e9, rayleigh), 0.0) << "never negative";
  SkyFromReport mist = sky_from_metar(parse_metar("KORD 271751Z 19012KT 3SM BR OVC008 08/07 A2978"));
  ASSERT_TRUE(mist.visibility_m);
  EXPECT_DOUBLE_EQ(*mist.visibility_m, 3 * 1609.344);
  EXPECT_FALSE(sky_from_metar(parse_metar("KPHX 271751Z 26006KT P6SM SKC 31/M04 A2985")).visibility_m);
  EXPECT_FALSE(sky_from_metar(parse_metar("EGLL 271750Z VRB03KT CAVOK 12/08 Q1021")).visibility_m);
}

TEST(SkyFromMetar, ClearSkiesAndVariableWind) {
  for (const char* r :
       {"EGLL 271750Z VRB03KT CAVOK 12/08 Q1021", "KPHX 271751Z 26006KT P6SM SKC 31/M04 A2985",
        "LEMD 271800Z 04006KT 9999 NSC 13/01 Q1026", "KMEM 230853Z AUTO 18014G18KT 10SM CLR 16/M02 A3008"})
    EXPECT_TRUE(sky_from_metar(parse_metar(r)).layers.empty()) << r;
  EXPECT_EQ(sky_from_metar(parse_metar("EGLL 271750Z VRB03KT CAVOK 12/08 Q1021")).wind_mps, glm::vec2(0.0f));
  // A wind from the north (360) drifts the clouds south.
  glm::vec2 north = sky_from_metar(parse_metar("KXYZ 010000Z 36010MPS 9999 SKC 10/05 Q1013")).wind_mps;
  EXPECT_NEAR(north.x, 0.0f, 1e-5);
  EXPECT_NEAR(north.y, -10.0f, 1e-5);
}

}  // namespace
