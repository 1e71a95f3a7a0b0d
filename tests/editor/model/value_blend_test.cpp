// Reflection-driven blending and diffing of JSON values.
#include "model/value_blend.h"

#include <gtest/gtest.h>

#include "model/reflected_object.h"
#include "test_module.h"
#include "welkin/core/error.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using editor_test::Clouds;
using nlohmann::json;

TEST(ValueBlend, ArraysOfDifferentLengthsSwitchHalfway) {
  const TypeDesc& t = type_desc<Clouds>();
  json a = default_component_json(t), b = a;
  b["layers"].push_back(json{{"coverage", 1.0}, {"octaves", 8}});
  EXPECT_EQ(blend_object_json(t, a, b, 0.4)["layers"].size(), 1u);
  EXPECT_EQ(blend_object_json(t, a, b, 0.6)["layers"].size(), 2u);
}

TEST(ValueBlend, BooleansSwitchHalfwayIntegersRound) {
  const TypeDesc& t = type_desc<Clouds>();
  json a = default_component_json(t), b = a;
  a["shadows"] = false;
  a["steps"] = 1;
  b["steps"] = 4;
  json m = blend_object_json(t, a, b, 0.5);
  EXPECT_EQ(m["shadows"], json(true));
  EXPECT_EQ(m["steps"], json(3));  // 2.5 rounds away from zero
}

TEST(ValueBlend, DifferencesWalkIntoArraysOfStructs) {
  const TypeDesc& t = type_desc<Clouds>();
  json a = default_component_json(t), b = a;
  b["tint"][2] = 0.5;
  b["layers"][0]["octaves"] = 2;
  EXPECT_EQ(differing_fields(t, a, b), (std::vector<std::string>{"tint", "layers/0/octaves"}));
  b["layers"].push_back(b["layers"][0]);
  EXPECT_EQ(differing_fields(t, a, b), (std::vector<std::string>{"tint", "layers"}));
  EXPECT_TRUE(differing_fields(t, a, a).empty());
}

TEST(ReflectedObject, CompleteJsonFillsDefaultsAndValidates) {
  const TypeDesc& t = type_desc<Clouds>();
  json c = complete_component_json(t, json{{"density", 2}});
  EXPECT_EQ(c["density"], json(2.0));
  EXPECT_EQ(c["label"], json("cumulus"));
  EXPECT_THROW(complete_component_json(t, json{{"density", -1}}), welkin::Error);
}

}  // namespace
