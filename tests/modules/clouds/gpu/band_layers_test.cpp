// The march's altitude bands compile in only the layers that their samples and their light steps can
// reach (density_field.cpp's band_defines): the peer scene's haze at the ground, cumulus and cirrus.
// Leaving the others out changes no pixel (a layer adds nothing outside its altitudes; the goldens
// hold that) and spares a software rasteriser their code at every sample.
#include <fstream>

#include "clouds_test_support.h"
#include "density_field.h"

namespace welkin::clouds {
namespace {

// The peer scene (assets/scenes/clouds-peer.json: haze 0-300 m; cumulus 750-1400 m and 1000-2200 m and
// cirrus 7500-8000 m, each base varying by 150 m; light steps 80 m, three of them at `high`) under a
// sun `elevation_deg` up.
ShaderDefines peer_bands(double elevation_deg) {
  std::ifstream in(std::string(WELKIN_SOURCE_DIR) + "/assets/scenes/clouds-peer.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  test::entity_with(doc, "atmosphere.Sun")["components"]["atmosphere.Sun"]["elevation_deg"] = elevation_deg;
  test::Rendered r = test::render(doc, 16, 9);
  return band_defines(r.world->resource<CloudsGpu>());
}

TEST(CloudsBands, EachBandMarchesTheLayersItsLightStepsReach) {
  // Sun 10 degrees up: the light steps (640 m at most) climb about 150 m within the march's reach
  // (its far samples see the sun up to 4 degrees higher): each band reads its own layers alone.
  const ShaderDefines low_sun = peer_bands(10.0);
  EXPECT_EQ(low_sun.at("CLOUDS_BANDS"), "3");
  EXPECT_EQ(low_sun.at("CLOUDS_BAND_LAYERS_0"), "8");  // the haze (layer 3)
  EXPECT_EQ(low_sun.at("CLOUDS_BAND_LAYERS_1"), "3");  // the two cumulus layers
  EXPECT_EQ(low_sun.at("CLOUDS_BAND_LAYERS_2"), "4");  // the cirrus
  // Sun 80 degrees up: the haze's light steps climb to about 940 m, past both cumulus layers' lowest
  // bases (600 and 850 m).
  const ShaderDefines high_sun = peer_bands(80.0);
  EXPECT_EQ(high_sun.at("CLOUDS_BAND_LAYERS_0"), "11");
  EXPECT_EQ(high_sun.at("CLOUDS_BAND_LAYERS_1"), "3");
  EXPECT_EQ(high_sun.at("CLOUDS_BAND_LAYERS_2"), "4");
}

}  // namespace
}  // namespace welkin::clouds
