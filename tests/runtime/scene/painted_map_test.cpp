#include "welkin/scene/painted_map.h"

#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "welkin/core/error.h"
#include "welkin/gfx/image.h"
#include "scratch_folder.h"

namespace {

namespace fs = std::filesystem;
using welkin::MapFrame;

fs::path temp_dir() {
  return welkin::testing::scratch_folder("welkin-painted-map-test");
}

TEST(MapFrame, TheOriginIsTheCentreAndAColumnOfAirStaysOnOnePlace) {
  const MapFrame f{.size_m = 100000.0};
  const glm::dvec2 c = f.uv({0.0, 0.0, 0.0});
  EXPECT_NEAR(c.x, 0.5, 1e-12);
  EXPECT_NEAR(c.y, 0.5, 1e-12);
  // 20 km east along the ground is 20 km along the tangent plane after the gnomonic projection:
  // R tan(20 km / R).
  const double R = f.planet_radius_m, a = 20000.0 / R;
  const glm::dvec3 ground = f.planet_center_m + R * glm::dvec3(std::sin(a), 0.0, std::cos(a));
  EXPECT_NEAR(f.uv(ground).x, 0.5 + R * std::tan(a) / f.size_m, 1e-12);
  EXPECT_NEAR(f.uv(ground).y, 0.5, 1e-12);
  // North is up on the map (smaller y); the same column at 8 km of altitude reads the same texel.
  const glm::dvec3 north = f.planet_center_m + R * glm::dvec3(0.0, std::sin(a), std::cos(a));
  EXPECT_LT(f.uv(north).y, 0.5);
  const glm::dvec3 high = f.planet_center_m + (R + 8000.0) * glm::normalize(north - f.planet_center_m);
  EXPECT_NEAR(glm::distance(f.uv(high), f.uv(north)), 0.0, 1e-12);
  // The far side of the planet is on no map.
  EXPECT_LT(f.uv(f.planet_center_m * 2.0).x, 0.0);
}

TEST(MapFrame, GroundPointAndPlaceRoundTripForAnyPlanetCentre) {
  for (const glm::dvec3 centre : {glm::dvec3(0, 0, -6360000.0), glm::dvec3(1e6, -3e6, -5e6), glm::dvec3(-6360000.0, 0, 0)}) {
    const MapFrame f{.planet_center_m = centre, .planet_radius_m = glm::length(centre), .size_m = 250000.0};
    const glm::dmat3 a = f.axes();
    EXPECT_NEAR(glm::dot(a[0], a[1]), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(glm::cross(a[0], a[1]) - a[2]), 0.0, 1e-12) << "east, north, up is right-handed";
    for (const glm::dvec2 uv : {glm::dvec2(0.1, 0.9), glm::dvec2(0.5, 0.5), glm::dvec2(0.73, 0.21)}) {
      const glm::dvec3 p = f.ground_point(uv);
      EXPECT_NEAR(glm::length(p - centre), f.planet_radius_m, 1e-6);
      EXPECT_NEAR(glm::distance(f.uv(p), uv), 0.0, 1e-9);
    }
  }
}

TEST(PaintedMaps, ABrushMovesTexelsTowardItsTargetInsideItsRadiusOnly) {
  welkin::PaintedMaps maps;
  welkin::PaintedMap& m = maps.create("unused.png", 32);
  EXPECT_TRUE(m.unsaved);
  const welkin::BrushStamp s{.cx = 10.0, .cy = 12.0, .radius_texels = 4.0, .strength = 0.5, .target = 255};
  const welkin::MapRegion b = welkin::brush_bounds(m, s);
  EXPECT_EQ(b.x, 6);
  EXPECT_EQ(b.width, 8);
  welkin::apply_brush(m, s);
  // The texel at the centre: d = hypot(0.5, 0.5) / 4, falloff 1 - d^2 (3 - 2 d).
  const double d = std::hypot(0.5, 0.5) / 4.0, falloff = 1.0 - d * d * (3.0 - 2.0 * d);
  EXPECT_EQ(m.at(10, 12), uint8_t(std::lround(128 + 127 * 0.5 * falloff)));
  EXPECT_EQ(m.at(15, 12), welkin::kPaintedMapNeutral) << "outside the radius";
  EXPECT_EQ(m.at(10, 17), welkin::kPaintedMapNeutral);
  EXPECT_GT(m.at(12, 12), welkin::kPaintedMapNeutral);
  EXPECT_LT(m.at(12, 12), m.at(10, 12)) << "weaker toward the rim";
  // A stamp entirely off the map changes nothing and reports no rectangle.
  EXPECT_EQ(welkin::brush_bounds(m, {.cx = -20.0, .cy = 5.0}).width, 0);
}

TEST(PaintedMaps, RegionsCopyAndPasteBackExactly) {
  welkin::PaintedMaps maps;
  welkin::PaintedMap& m = maps.create("unused.png", 16);
  const welkin::BrushStamp s{.cx = 4.0, .cy = 5.0, .radius_texels = 3.0, .strength = 1.0, .target = 0};
  const welkin::MapRegion b = welkin::brush_bounds(m, s);
  const welkin::MapRegion before = welkin::copy_region(m, b.x, b.y, b.width, b.height);
  welkin::apply_brush(m, s);
  EXPECT_LT(m.at(4, 5), 20);
  welkin::paste_region(m, before);
  for (uint8_t t : m.texels) EXPECT_EQ(t, welkin::kPaintedMapNeutral);
  EXPECT_THROW(welkin::paste_region(m, welkin::MapRegion{14, 14, 4, 4, std::vector<uint8_t>(16)}), welkin::Error);
}

TEST(PaintedMaps, SavedMapsReadBackAndOnlyChangedOnesAreWritten) {
  const fs::path file = temp_dir() / "coverage.png";
  fs::remove(file);
  {
    welkin::PaintedMaps maps;
    welkin::PaintedMap& m = maps.create(file.string(), 8);
    m.texels[3 * 8 + 5] = 7;
    maps.save_unsaved();
    EXPECT_FALSE(m.unsaved);
    ASSERT_TRUE(fs::exists(file));
    const auto written = fs::last_write_time(file);
    fs::last_write_time(file, written - std::chrono::hours(1));
    maps.save_unsaved();  // nothing changed since: not written again
    EXPECT_EQ(fs::last_write_time(file), written - std::chrono::hours(1));
  }
  welkin::PaintedMaps again;
  const welkin::PaintedMap& m = again.get(file.string());
  EXPECT_EQ(m.side, 8);
  EXPECT_EQ(m.at(5, 3), 7);
  EXPECT_EQ(m.at(0, 0), welkin::kPaintedMapNeutral);
  EXPECT_FALSE(m.unsaved);
}

TEST(PaintedMaps, AMapThatIsNotSquareOrMissingIsOneErrorNamingTheFile) {
  const fs::path file = temp_dir() / "wide.png";
  welkin::write_png(file.string(), welkin::ImageU8{4, 2, std::vector<uint8_t>(32, 200)});
  welkin::PaintedMaps maps;
  try {
    maps.get(file.string());
    FAIL() << "a 4 x 2 map was accepted";
  } catch (const welkin::Error& e) {
    EXPECT_EQ(e.info().file, file.string());
    EXPECT_NE(e.info().found.find("4 x 2"), std::string::npos);
  }
  EXPECT_THROW(maps.get((temp_dir() / "missing.png").string()), welkin::Error);

  // A map larger than 4096 a side is refused from its header, before anything is decoded: this file
  // is a valid PNG header for 8000 x 8000 grey texels with no image data at all.
  const fs::path big = temp_dir() / "big.png";
  {
    const uint8_t header[] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                              0, 0, 0x1f, 0x40, 0, 0, 0x1f, 0x40, 8, 0, 0, 0, 0, 0, 0, 0, 0,
                              0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    std::ofstream(big, std::ios::binary).write(reinterpret_cast<const char*>(header), sizeof(header));
  }
  try {
    maps.get(big.string());
    FAIL() << "an 8000 x 8000 map was accepted";
  } catch (const welkin::Error& e) {
    EXPECT_EQ(e.info().file, big.string());
    EXPECT_NE(e.info().expected.find("4096"), std::string::npos) << e.what();
    EXPECT_NE(e.info().found.find("8000x8000"), std::string::npos) << e.what();
  }
  EXPECT_THROW(maps.create("x.png", 0), welkin::Error);
  EXPECT_THROW(maps.create("x.png", welkin::kMaxPaintedMapSide + 1), welkin::Error);
}

}  // namespace
