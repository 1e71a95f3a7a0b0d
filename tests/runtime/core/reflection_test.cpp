#include "welkin/core/reflection.h"

#include <gtest/gtest.h>

#include "error_of.h"

#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/json_fields.h"

namespace {

struct Layer {
  static constexpr std::string_view kTypeName = "test.Layer";
  float coverage = 0.5f;
  double altitude_km = 1.5;
};
void describe(welkin::TypeBuilder<Layer>& t) {
  t.field("coverage", &Layer::coverage).range(0, 1).tooltip("Fraction of sky covered");
  t.field("altitude_km", &Layer::altitude_km).unit("km").range(0, 20);
}

enum class Phase : int { rayleigh = 0, mie = 3 };

struct Sky {
  static constexpr std::string_view kTypeName = "test.Sky";
  bool enabled = true;
  int samples = 16;
  float g = 0.8f;
  glm::vec2 uv{0.25f, 0.75f};
  glm::vec3 tint{0.1f, 0.2f, 0.3f};
  glm::vec4 params{1, 2, 3, 4};
  glm::dvec3 origin{6.36e6, -1.0, 0.1};
  Phase phase = Phase::mie;
  std::string name = "sky";
  std::vector<Layer> layers{Layer{}, Layer{0.9f, 8.0}};
};
void describe(welkin::TypeBuilder<Sky>& t) {
  t.field("enabled", &Sky::enabled);
  t.field("samples", &Sky::samples).range(1, 256);
  t.field("g", &Sky::g).range(-0.999, 0.999);
  t.field("uv", &Sky::uv);
  t.field("tint", &Sky::tint).color().range(0, 1);
  t.field("params", &Sky::params);
  t.field("origin", &Sky::origin).unit("m");
  t.field("phase", &Sky::phase).values({{"rayleigh", 0}, {"mie", 3}});
  t.field("name", &Sky::name);
  t.field("layers", &Sky::layers).max_count(4);
}

using nlohmann::json;
using welkin::type_desc;

using welkin::testing::error_of;

TEST(Reflection, DescribesKindsUnitsRangesAndDefaults) {
  const auto& d = type_desc<Sky>();
  EXPECT_EQ(d.name, "test.Sky");
  ASSERT_EQ(d.fields.size(), 10u);
  EXPECT_EQ(d.field("tint")->kind, welkin::FieldKind::color);
  EXPECT_EQ(d.field("origin")->kind, welkin::FieldKind::dvec3);
  EXPECT_EQ(d.field("origin")->unit, "m");
  EXPECT_EQ(d.field("phase")->kind, welkin::FieldKind::enumeration);
  EXPECT_EQ(d.field("layers")->element->name, "test.Layer");
  EXPECT_EQ(*d.field("g")->max, 0.999);
  EXPECT_EQ(d.field("layers")->element->field("coverage")->tooltip, "Fraction of sky covered");
  EXPECT_EQ(static_cast<const Sky*>(d.defaults.get())->samples, 16);
  EXPECT_EQ(d.field("samples")->offset, offsetof(Sky, samples));
}

TEST(Reflection, JsonRoundTripIsExact) {
  Sky a;
  a.g = 0.1f;  // not representable: must still round-trip bit-exactly
  a.tint = {0.3f, 0.7f, 1e-7f};
  a.origin = {1.0 / 3.0, -2e9 / 7.0, 0.0};
  a.phase = Phase::rayleigh;
  a.layers.push_back(Layer{0.123456789f, 19.99});
  a.name = "quote\" and unicode \u00e9";
  json j = welkin::object_to_json(type_desc<Sky>(), &a);
  EXPECT_EQ(j["g"], json(0.1)) << "floats are written as their shortest decimal";
  EXPECT_EQ(j["phase"], "rayleigh");
  Sky b;
  welkin::object_from_json(type_desc<Sky>(), &b, json::parse(j.dump()));
  EXPECT_EQ(b.g, a.g);
  EXPECT_EQ(b.tint, a.tint);
  EXPECT_EQ(b.origin, a.origin);
  EXPECT_EQ(b.phase, a.phase);
  EXPECT_EQ(b.name, a.name);
  ASSERT_EQ(b.layers.size(), 3u);
  EXPECT_EQ(b.layers[2].coverage, a.layers[2].coverage);
  EXPECT_EQ(b.layers[2].altitude_km, a.layers[2].altitude_km);
  EXPECT_EQ(welkin::object_to_json(type_desc<Sky>(), &b), j);
}

TEST(Reflection, ReadingValidatesAndNamesThePath) {
  Sky s;
  auto read = [&](const char* text) { return error_of([&] { welkin::object_from_json(type_desc<Sky>(), &s, json::parse(text)); }); };
  EXPECT_NE(read(R"({"g": 1.5})").find("at /g"), std::string::npos);
  EXPECT_NE(read(R"({"g": 1.5})").find("out of range"), std::string::npos);
  EXPECT_NE(read(R"({"samples": 2.5})").find("expected integer"), std::string::npos);
  EXPECT_NE(read(R"({"tint": [1, 0]})").find("at /tint"), std::string::npos);
  EXPECT_NE(read(R"({"tint": [1, 0, 2]})").find("at /tint/2"), std::string::npos);
  EXPECT_NE(read(R"({"phase": "hg"})").find("one of \"rayleigh\", \"mie\""), std::string::npos);
  EXPECT_NE(read(R"({"layers": [{"coverage": 0.5}, {"coverag": 1}]})").find("at /layers/1/coverag"), std::string::npos);
  EXPECT_NE(read(R"({"layers": [{}, {}, {}, {}, {}]})").find("at most 4"), std::string::npos);
  EXPECT_NE(read(R"({"enabled": 1})").find("true or false"), std::string::npos);
  EXPECT_NE(read(R"({"bogus": 1})").find("unknown field"), std::string::npos);
  EXPECT_EQ(read(R"({"g": -0.5, "layers": []})"), "no error");
  EXPECT_EQ(s.g, -0.5f);
  EXPECT_TRUE(s.layers.empty());
}

// An array read from a document is the document's: an element starts from its type's defaults, not
// from the element the defaults held at its index (Sky's second default layer is {0.9, 8 km}).
TEST(Reflection, ArrayElementsStartFromTheirTypesDefaults) {
  Sky s;
  welkin::object_from_json(type_desc<Sky>(), &s, json::parse(R"({"layers": [{"coverage": 0.2}, {"coverage": 0.3}]})"));
  ASSERT_EQ(s.layers.size(), 2u);
  EXPECT_EQ(s.layers[0].coverage, 0.2f);
  EXPECT_EQ(s.layers[0].altitude_km, 1.5);
  EXPECT_EQ(s.layers[1].coverage, 0.3f);
  EXPECT_EQ(s.layers[1].altitude_km, 1.5) << "not the default second layer's 8 km";
  // A document that names every field reads back the same whatever the defaults held.
  Sky a;
  a.layers = {Layer{0.9f, 8.0}};
  Sky b;
  b.layers.clear();
  welkin::object_from_json(type_desc<Sky>(), &b, welkin::object_to_json(type_desc<Sky>(), &a));
  ASSERT_EQ(b.layers.size(), 1u);
  EXPECT_EQ(b.layers[0].altitude_km, 8.0);
}

TEST(FieldPath, ResolvesNestedArraysAndVectorComponents) {
  Sky s;
  const auto& d = type_desc<Sky>();
  auto cov = welkin::resolve_field(d, &s, "layers/1/coverage");
  EXPECT_FLOAT_EQ(cov.get_scalar(), 0.9f);
  cov.set_scalar(0.25);
  EXPECT_EQ(s.layers[1].coverage, 0.25f);
  auto tint_g = welkin::resolve_field(d, &s, "tint/1");
  tint_g.set_scalar(0.5);
  EXPECT_EQ(s.tint, glm::vec3(0.1f, 0.5f, 0.3f));
  welkin::resolve_field(d, &s, "phase").set_json("rayleigh");
  EXPECT_EQ(s.phase, Phase::rayleigh);
  EXPECT_NE(error_of([&] { welkin::resolve_field(d, &s, "layers/7/coverage"); }).find("index below 2"), std::string::npos);
  EXPECT_NE(error_of([&] { welkin::resolve_field(d, &s, "layers/0/nope"); }).find("/layers/0/nope"), std::string::npos);
  EXPECT_NE(error_of([&] { welkin::resolve_field(d, &s, "tint/3"); }).find("component index"), std::string::npos);
  EXPECT_NE(error_of([&] { welkin::resolve_field(d, &s, "g").set_scalar(2.0); }).find("out of range"), std::string::npos);
  EXPECT_NE(error_of([&] { welkin::resolve_field(d, &s, "g").set_scalar(std::nan("")); }).find("finite"), std::string::npos);
  EXPECT_EQ(s.g, 0.8f) << "a rejected value leaves the field unchanged";
}

}  // namespace
