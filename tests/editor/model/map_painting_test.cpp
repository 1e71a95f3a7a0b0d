// Painting a module's map in the editor: a map panel declared as data, a brush stroke as one undo
// step that restores every texel, the map written beside the scene with it, and the script verbs.
#include "model/map_painting.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "model/script.h"
#include "test_module.h"
#include "welkin/core/error.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
using editor_test::ScratchDir;
using nlohmann::json;

const MapFieldSpec kWeatherMap{"test.Weather", "map", "map_size_m"};
constexpr const char* kPanels =
    R"({"panels": [{"title": "Weather map", "map": {"component": "test.Weather", "file_field": "map", "size_field": "map_size_m"}}]})";

TEST(ModulePanels, AMapPanelNamesItsComponentsFields) {
  ScratchDir dir("map-panel");
  editor_test::test_module_data_dir() = dir.path().string();
  dir.write("editor/panels.json", kPanels);
  auto world = editor_test::make_test_world();
  std::vector<std::string> errors;
  auto specs = read_module_panels(world->modules(), errors);
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(specs[0].map, kWeatherMap);
  EXPECT_TRUE(specs[0].components.empty());
  // Both kinds in one panel, or a map of another module's component, are errors naming the place.
  dir.write("editor/panels.json", R"({"panels": [{"title": "W", "components": ["test.Fog"], "map": {"component": "test.Weather", "file_field": "map", "size_field": "map_size_m"}}]})");
  EXPECT_TRUE(read_module_panels(world->modules(), errors).empty());
  dir.write("editor/panels.json", R"({"panels": [{"title": "W", "map": {"component": "other.Weather", "file_field": "map", "size_field": "s"}}]})");
  EXPECT_TRUE(read_module_panels(world->modules(), errors).empty());
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("/panels/0"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("/panels/0/map/component"), std::string::npos) << errors[1];
}

class MapPainting : public ::testing::Test {
 protected:
  MapPainting() : dir("map-painting"), doc(editor_test::make_test_world) {
    editor_test::test_module_data_dir() = dir.path().string();
    dir.write("editor/panels.json", kPanels);
    doc.new_scene();
    doc.add_entity("weather", json{{"test.Weather", json::object()}});
    scene = (dir.path() / "valley.json").string();
    doc.save_scene(scene);
  }
  std::vector<uint8_t> texels() { return doc.world().resource<PaintedMaps>().get(find_map(doc, kWeatherMap).file).texels; }
  ScratchDir dir;
  EditorDocument doc;
  std::string scene;
};

TEST_F(MapPainting, ANewMapIsNeutralBesideTheSceneAndUndoable) {
  const std::string file = new_map(doc, kWeatherMap, 32);
  EXPECT_EQ(file, (dir.path() / "valley.map.png").string());
  EXPECT_EQ(find_map(doc, kWeatherMap).file, file);
  EXPECT_EQ(texels(), std::vector<uint8_t>(32 * 32, kPaintedMapNeutral));
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(find_map(doc, kWeatherMap).file, "");
  // Without a saved scene there is nowhere to put one.
  EditorDocument unsaved(editor_test::make_test_world);
  unsaved.add_entity("weather", json{{"test.Weather", json::object()}});
  EXPECT_THROW(new_map(unsaved, kWeatherMap, 32), Error);
  EXPECT_THROW(paint_at(unsaved, kWeatherMap, {0, 0, 0}, MapBrush{}), Error);  // no map to paint
}

TEST_F(MapPainting, ANewMapTakesAFreeNameSoUndoGivesBackWhatTheFieldNamed) {
  // The scene names a file that is not there: the document has no map.
  const std::string named = (dir.path() / "valley.map.png").string();
  doc.set_field(find_map(doc, kWeatherMap).entity, "test.Weather", "map", named);
  PaintedMaps& maps = doc.world().resource<PaintedMaps>();
  EXPECT_THROW(maps.get(named), Error);
  const std::string file = new_map(doc, kWeatherMap, 16);
  EXPECT_EQ(file, (dir.path() / "valley.map-2.png").string());  // the field's own name would be no edit
  EXPECT_TRUE(std::filesystem::exists(file));                   // written at once
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(find_map(doc, kWeatherMap).file, named);
  EXPECT_THROW(maps.get(named), Error);  // no map, as before; the new file stays on disk
  EXPECT_TRUE(doc.redo());
  EXPECT_EQ(texels(), std::vector<uint8_t>(16 * 16, kPaintedMapNeutral));
  // The first name stays taken while the history holds it (undoing to it must find no map there),
  // and a file already there is never replaced.
  EXPECT_EQ(new_map(doc, kWeatherMap, 32), (dir.path() / "valley.map-3.png").string());
  EXPECT_EQ(maps.get(file).side, 16);
  EXPECT_TRUE(doc.undo() && doc.undo());
  EXPECT_EQ(find_map(doc, kWeatherMap).file, named);
  EXPECT_THROW(maps.get(named), Error);
}

TEST_F(MapPainting, AStrokeIsOneStepThatRestoresEveryTexel) {
  new_map(doc, kWeatherMap, 64);
  const std::vector<uint8_t> neutral = texels();
  const size_t steps = doc.history().steps().size();
  // A drag from west to east across the map's middle: 2 km brush on a 20 km map of 64 texels.
  MapBrush brush{.radius_m = 2000.0, .strength = 0.6, .mode = BrushMode::add};
  for (double east = -6000.0; east <= 6000.0; east += 500.0) EXPECT_TRUE(paint_at(doc, kWeatherMap, {east, 0.0, 0.0}, brush, true));
  doc.end_continuous_edit();
  EXPECT_EQ(doc.history().steps().size(), steps + 1);
  const std::vector<uint8_t> painted = texels();
  const PaintedMap& map = doc.world().resource<PaintedMaps>().get(find_map(doc, kWeatherMap).file);
  EXPECT_GT(map.at(32, 32), 240);  // the stroke's middle, stamped over and over
  EXPECT_EQ(map.at(32, 5), kPaintedMapNeutral);  // 8.6 km north: untouched
  EXPECT_EQ(map.at(2, 32), kPaintedMapNeutral);  // west of where the stroke began
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(texels(), neutral);
  EXPECT_TRUE(doc.redo());
  EXPECT_EQ(texels(), painted);
  // A second stroke clears part of the first; undo returns to the first exactly.
  paint_at(doc, kWeatherMap, {0.0, 0.0, 0.0}, MapBrush{.radius_m = 3000.0, .strength = 1.0, .mode = BrushMode::clear});
  EXPECT_LE(doc.world().resource<PaintedMaps>().get(find_map(doc, kWeatherMap).file).at(32, 32), 5);  // near the centre: full strength
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(texels(), painted);
  // Off the map (30 km east of a 20 km map): nothing painted, no step.
  const size_t before = doc.history().steps().size();
  EXPECT_FALSE(paint_at(doc, kWeatherMap, {30000.0, 0.0, 0.0}, brush));
  EXPECT_EQ(doc.history().steps().size(), before);
}

TEST_F(MapPainting, ScriptPaintsUndoesSavesAndReloads) {
  std::string output;
  PresetLibrary presets(editor_test::make_test_world());
  EditorDocument* current = &doc;
  auto run = [&](const std::string& text) {
    for (const ScriptLine& line : parse_script(text, "paint.script")) ASSERT_TRUE(run_document_verb(*current, presets, line, output)) << line.verb;
  };
  run("new-map test.Weather/map 64\n"
      "paint test.Weather/map 5000 0 2000 1 add\n"
      "expect-map test.Weather/map 5000 0 250 255\n"
      "expect-map test.Weather/map -5000 0 128 128\n"
      "paint test.Weather/map -5000 2000 1500 1 clear\n"
      "expect-map test.Weather/map -5000 2000 0 5\n"
      "undo\n"
      "expect-map test.Weather/map -5000 2000 128 128\n"
      "redo\n"
      "save-scene " + scene + "\n");
  EXPECT_NE(output.find("valley.map.png"), std::string::npos) << output;
  // Another session reads the scene and the map written beside it.
  EditorDocument again(editor_test::make_test_world);
  current = &again;
  run("load-scene " + scene + "\n"
      "expect-map test.Weather/map 5000 0 250 255\n"
      "expect-map test.Weather/map -5000 2000 0 5\n"
      "expect-map test.Weather/map 0 -8000 128 128\n");
  // Bad words name the line.
  try {
    run("paint test.Weather/map 0 0 1000 2 add\n");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.info().file, "paint.script:1");
  }
  EXPECT_THROW(run("paint test.Fog/visibility_km 0 0 1000 1 add\n"), Error);
}

TEST(RayAtAltitude, MeetsTheSphereAheadOfTheCamera) {
  const MapFrame frame;  // Earth's radius, centre below the origin
  // Straight up from the ground to 1500 m; straight down from 9 km to 1500 m.
  auto up = ray_at_altitude(frame, {0, 0, 100}, {0, 0, 1}, 1500.0);
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->z, 1500.0, 1e-6);
  auto down = ray_at_altitude(frame, {2000, 0, 9000}, {0, 0, -1}, 1500.0);
  ASSERT_TRUE(down);
  EXPECT_NEAR(glm::length(*down - frame.planet_center_m) - frame.planet_radius_m, 1500.0, 1e-6);
  // Horizontal at 100 m toward a sphere at 1500 m: it meets it where the curvature lifts it
  // (x^2 ~ 2 R (1500 - 100)), about 133.4 km away.
  auto far = ray_at_altitude(frame, {0, 0, 100}, {1, 0, 0}, 1500.0);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->x, std::sqrt(2.0 * 6361500.0 * 1400.0), 200.0);
  // From 9 km looking up, the 1500 m sphere is behind: no hit.
  EXPECT_FALSE(ray_at_altitude(frame, {0, 0, 9000}, {0, 0, 1}, 1500.0));
}

}  // namespace
