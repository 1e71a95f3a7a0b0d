// Bad cloud values in a scene file: one clear error naming the file and the field's path, before
// anything is drawn. Round trips keep every field.
#include "clouds_test_support.h"
#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

std::string load_error(const json& clouds) {
  World world;
  world.modules().add_static(welkin::modules::atmosphere_module());
  world.modules().add_static(welkin::modules::clouds_module());
  try {
    load_scene(world, test::noon(clouds), "bad.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CloudsComponents, BadLayerValuesNameTheFileAndTheField) {
  const std::string negative = load_error({{"layers", json::array({{{"thickness_m", -100}}})}});
  EXPECT_NE(negative.find("bad.json"), std::string::npos) << negative;
  EXPECT_NE(negative.find("clouds.VolumetricClouds/layers/0/thickness_m"), std::string::npos) << negative;

  const std::string nan = load_error({{"layers", json::array({{{"coverage", "nan"}}})}});
  EXPECT_NE(nan.find("layers/0/coverage"), std::string::npos) << nan;

  const std::string genus = load_error({{"layers", json::array({json::object(), {{"genus", "cumulonimbulus"}}})}});
  EXPECT_NE(genus.find("layers/1/genus"), std::string::npos) << genus;
  EXPECT_NE(genus.find("cumulonimbulus"), std::string::npos) << genus;

  const std::string steps = load_error({{"min_step_m", 500}, {"max_step_m", 100}});
  EXPECT_NE(steps.find("max_step_m"), std::string::npos) << steps;
  EXPECT_EQ(load_error(json::object()), "");
}

TEST(CloudsComponents, RoundTripKeepsEveryField) {
  VolumetricClouds c;
  c.layers = VolumetricClouds::default_layers();
  c.layers[1].genus = Genus::cirrocumulus;
  c.layers[0].wind_mps = {3.5f, -2.0f};
  c.phase = PhaseModel::droplet_mie;
  const json j = object_to_json(type_desc<VolumetricClouds>(), &c);
  VolumetricClouds back;
  object_from_json(type_desc<VolumetricClouds>(), &back, j);
  EXPECT_EQ(object_to_json(type_desc<VolumetricClouds>(), &back), j);
  EXPECT_EQ(back.layers[1].genus, Genus::cirrocumulus);
}

}  // namespace
}  // namespace welkin::clouds
