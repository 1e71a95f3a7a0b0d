// Bad cloud values in a scene file: one clear error naming the file and the field's path, before
// anything is drawn. Round trips keep every field.
#include <cstring>
#include <filesystem>
#include <set>

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

  // Work bounded before it is spent: custom marching that would take more than 65536 density samples
  // per ray is refused; the same values under a preset quality are not used, so not refused.
  const std::string work = load_error({{"quality", "custom"}, {"max_steps", 4096}, {"light_steps", 64}});
  EXPECT_NE(work.find("clouds.VolumetricClouds/max_steps"), std::string::npos) << work;
  EXPECT_NE(work.find("65536"), std::string::npos) << work;
  EXPECT_EQ(load_error({{"quality", "custom"}, {"max_steps", 1008}, {"light_steps", 64}}), "");
  EXPECT_EQ(load_error({{"quality", "high"}, {"max_steps", 4096}, {"light_steps", 64}}), "");
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

namespace welkin::clouds {
namespace {

// Every scene preset is a valid clouds.VolumetricClouds, every other preset of its own component.
TEST(CloudsPresets, EveryPresetFileLoads) {
  const std::filesystem::path dir = WELKIN_SOURCE_DIR "/modules/clouds/presets";
  int scenes = 0, clusters = 0, billboards = 0, lods = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".json") continue;
    // The other paths' presets (clusters-*, billboards-*, lod-*.json) are of their own components.
    const std::string name = e.path().filename().string();
    if (name.rfind("clusters-", 0) == 0) {
      CloudClusters k;
      EXPECT_NO_THROW(object_from_json(type_desc<CloudClusters>(), &k, read_json_file(e.path().string()))) << e.path();
      ++clusters;
      continue;
    }
    if (name.rfind("billboards-", 0) == 0) {
      CloudBillboards b;
      EXPECT_NO_THROW(object_from_json(type_desc<CloudBillboards>(), &b, read_json_file(e.path().string()))) << e.path();
      EXPECT_NO_THROW(validate(b)) << e.path();
      ++billboards;
      continue;
    }
    if (name.rfind("lod-", 0) == 0) {
      CloudLod l;
      EXPECT_NO_THROW(object_from_json(type_desc<CloudLod>(), &l, read_json_file(e.path().string()))) << e.path();
      ++lods;
      continue;
    }
    VolumetricClouds c;
    EXPECT_NO_THROW(object_from_json(type_desc<VolumetricClouds>(), &c, read_json_file(e.path().string()))) << e.path();
    EXPECT_FALSE(c.layers.empty()) << e.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 7);
  EXPECT_GE(clusters, 3);
  EXPECT_GE(billboards, 2);
  EXPECT_GE(lods, 1);
}

// The genus table (genera.h) and the preset folder agree: each row has its preset file, a valid layer
// of that genus holding the row's typical layer (thickness, density, shadow: the table is their source,
// which the weather module reads too), and each file in presets/genera is a row of the table. Nothing
// here counts genera.
TEST(CloudsPresets, TheGenusTableAndTheGeneraFolderAgree) {
  const std::filesystem::path dir = WELKIN_SOURCE_DIR "/modules/clouds/presets/genera";
  std::set<std::string> rows;
  for (int i = 0; i < kGenusCount; ++i) {
    const GenusTraits& g = kGenera[i];
    EXPECT_EQ(int(g.genus), i) << g.name;
    EXPECT_STREQ(genus_name(g.genus), g.name);
    EXPECT_TRUE(rows.insert(g.name).second) << g.name << " is in the table twice";
    const std::filesystem::path file = dir / (std::string(g.name) + ".json");
    ASSERT_TRUE(std::filesystem::is_regular_file(file)) << "no preset file for the genus " << g.name;
    CloudLayer layer;
    layer.genus = g.genus == Genus::cumulus ? Genus::stratus : Genus::cumulus;  // so a file without it fails
    const nlohmann::json preset = read_json_file(file.string());
    EXPECT_NO_THROW(object_from_json(type_desc<CloudLayer>(), &layer, preset)) << file;
    EXPECT_EQ(layer.genus, g.genus) << file;
    // Written in the file, not left to CloudLayer's defaults (a cumulus layer's).
    EXPECT_TRUE(preset.contains("thickness_m") && preset.contains("density_per_m")) << file;
    EXPECT_EQ(layer.thickness_m, g.thickness_m) << file;
    EXPECT_EQ(layer.density_per_m, g.density_per_m) << file;
    EXPECT_EQ(layer.casts_shadow, g.casts_shadow) << file;
  }
  std::set<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".json") files.insert(e.path().stem().string());
  EXPECT_EQ(files, rows);
  // The JSON reads and writes exactly the table's names.
  const FieldDesc* genus = type_desc<CloudLayer>().field("genus");
  ASSERT_NE(genus, nullptr);
  std::set<std::string> names;
  for (const EnumValue& v : genus->enum_values) names.insert(v.name);
  EXPECT_EQ(names, rows);
  EXPECT_THROW(genus_name(Genus(kGenusCount)), Error);
  EXPECT_THROW(genus_traits(Genus(-1)), Error);
}

}  // namespace
}  // namespace welkin::clouds

namespace welkin::clouds {
namespace {

// Solo and visible, as in a mixer: a soloed layer is drawn alone and exactly as it is among the
// others (its block, weather channel included, does not change); a hidden one is not packed.
TEST(CloudsComponents, SoloAndHiddenLayersPackAsInAMixer) {
  VolumetricClouds c;
  c.layers = {CloudLayer{}, CloudLayer{.genus = Genus::altostratus, .base_altitude_m = 5000}, CloudLayer{.base_altitude_m = 8000}};
  const CloudsContext ctx;
  const glm::dvec3 camera(0.0, 0.0, 100.0);
  const PackedLayers all = pack_layers(c, ctx, camera);
  ASSERT_EQ(all.source_index, (std::vector<int>{0, 1, 2}));
  c.layers[1].solo = true;
  const PackedLayers solo = pack_layers(c, ctx, camera);
  ASSERT_EQ(solo.source_index, (std::vector<int>{1}));
  EXPECT_EQ(std::memcmp(&solo.layers[0], &all.layers[1], sizeof(LayerBlock)), 0);
  c.layers[2].solo = true;
  EXPECT_EQ(pack_layers(c, ctx, camera).source_index, (std::vector<int>{1, 2}));
  c.layers[1].solo = c.layers[2].solo = false;
  c.layers[0].visible = false;
  const PackedLayers hidden = pack_layers(c, ctx, camera);
  ASSERT_EQ(hidden.source_index, (std::vector<int>{1, 2}));
  EXPECT_EQ(std::memcmp(&hidden.layers[1], &all.layers[2], sizeof(LayerBlock)), 0);
}

}  // namespace
}  // namespace welkin::clouds
