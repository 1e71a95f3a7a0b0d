// Components, validation, presets, uniforms and the LUT cache of the atmosphere module.
#include <unistd.h>

#include <filesystem>
#include <optional>

#include "cache_folder.h"
#include "gpu_test_support.h"
#include "welkin/atmosphere/presets.h"
#include "welkin/core/error.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/scene/json_fields.h"
#include "scratch_folder.h"

namespace welkin::atmosphere {
namespace {

using nlohmann::json;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// What the render system runs on values built in code: ranges, finiteness and cross-field checks.
template <class T> void validate_all(const T& v) {
  try {
    check_object(type_desc<T>(), &v);
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(T::kTypeName));
  }
}

TEST(AtmosphereValidation, DefaultsAreValid) {
  EXPECT_NO_THROW(validate_all(Atmosphere{}));
  EXPECT_NO_THROW(validate_all(Sun{}));
  EXPECT_NO_THROW(validate_all(Moon{}));
}

TEST(AtmosphereValidation, TopNotAboveBottomNamesTheField) {
  Atmosphere a;
  a.top_radius_km = a.bottom_radius_km;
  std::string msg = error_of([&] { validate_all(a); });
  EXPECT_NE(msg.find("atmosphere.Atmosphere/top_radius_km"), std::string::npos) << msg;
  EXPECT_NE(msg.find("greater than bottom_radius_km"), std::string::npos) << msg;
}

TEST(AtmosphereValidation, NegativeNaNAndAnisotropyAreRejected) {
  Atmosphere a;
  a.rayleigh_scattering.y = -1e-3f;
  EXPECT_NE(error_of([&] { validate_all(a); }).find("rayleigh_scattering/1"), std::string::npos);
  a = Atmosphere{};
  a.mie_density[0].exp_scale_per_km = std::nanf("");
  EXPECT_NE(error_of([&] { validate_all(a); }).find("mie_density/0/exp_scale_per_km"), std::string::npos);
  a = Atmosphere{};
  a.mie_g = 1.0f;
  EXPECT_NE(error_of([&] { validate_all(a); }).find("mie_g"), std::string::npos);
  a = Atmosphere{};
  a.mie_extinction = a.mie_scattering * 0.5f;
  EXPECT_NE(error_of([&] { validate_all(a); }).find("absorption cannot be negative"), std::string::npos);
  Sun s;
  s.elevation_deg = std::nanf("");
  EXPECT_NE(error_of([&] { validate_all(s); }).find("atmosphere.Sun/elevation_deg"), std::string::npos);
}

TEST(AtmosphereValidation, SceneFileErrorsNameFileAndPath) {
  World world;
  world.modules().add_static(welkin::modules::atmosphere_module());
  json doc = test::scene(json::object(), {{"mie_g", 1.0}});
  std::string msg = error_of([&] { load_scene(world, doc, "bad.json"); });
  EXPECT_NE(msg.find("bad.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mie_g"), std::string::npos) << msg;
  json layers = test::scene(
      json::object(), {{"rayleigh_density", json::array({json::object(), json::object(), json::object()})}});
  msg = error_of([&] {
    World w;
    w.modules().add_static(welkin::modules::atmosphere_module());
    load_scene(w, layers, "l.json");
  });
  EXPECT_NE(msg.find("at most 2"), std::string::npos) << msg;
  // Cross-field checks run while loading, so they too name the file and the entity's path.
  json inverted = test::scene(json::object(), {{"bottom_radius_km", 6360}, {"top_radius_km", 6000}});
  msg = error_of([&] {
    World w;
    w.modules().add_static(welkin::modules::atmosphere_module());
    load_scene(w, inverted, "inverted.json");
  });
  EXPECT_NE(msg.find("inverted.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("components/atmosphere.Atmosphere/top_radius_km"), std::string::npos) << msg;
}

TEST(AtmosphereValidation, RenderingAnInvalidAtmosphereThrowsOneError) {
  json doc = test::scene(json::object(), {{"bottom_radius_km", 6400}, {"top_radius_km", 6300}});
  std::string msg = error_of([&] { test::render(doc, 8, 8); });
  EXPECT_NE(msg.find("top_radius_km"), std::string::npos) << msg;
}

TEST(AtmospherePresets, AllLoadAndEarthIsTheDefault) {
  auto dir = preset_dir(std::filesystem::path(WELKIN_SOURCE_DIR) / "modules/atmosphere");
  auto names = preset_names(dir);
  for (const char* expected : {"earth", "earth-hazy", "mars", "clear-high-altitude"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  for (const auto& n : names) EXPECT_NO_THROW(load_preset_file(dir / (n + ".json"))) << n;
  Atmosphere earth = load_preset_file(dir / "earth.json"), def;
  EXPECT_EQ(earth.bottom_radius_km, def.bottom_radius_km);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(earth.rayleigh_scattering[c], def.rayleigh_scattering[c], 1e-9);
    EXPECT_NEAR(earth.absorption_extinction[c], def.absorption_extinction[c], 1e-9);
  }
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(earth.absorption_density[i].linear_term_per_km, def.absorption_density[i].linear_term_per_km,
                1e-6);
    EXPECT_NEAR(earth.absorption_density[i].constant_term, def.absorption_density[i].constant_term, 1e-6);
  }
  Atmosphere hazy = load_preset_file(dir / "earth-hazy.json");
  EXPECT_NEAR(hazy.mie_extinction.x, 0.021 * 1.1, 1e-7);
}

TEST(AtmospherePresets, BadPresetNamesFileAndPath) {
  auto file = welkin::testing::scratch_folder("welkin-atmosphere-test") / "welkin-bad-preset.json";
  write_file_atomically(file.string(), R"({"mie_g": 2})");
  std::string msg = error_of([&] { load_preset_file(file); });
  EXPECT_NE(msg.find("welkin-bad-preset.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mie_g"), std::string::npos) << msg;
  std::filesystem::remove(file);
}

TEST(AtmosphereUniforms, CameraRelativeToAnyPlanetCentre) {
  // Far from the scene origin in double, the float uniforms still hold the camera to the metre.
  Atmosphere a;
  a.planet_center_below_origin = false;
  a.planet_center_m = {1.0e9, -2.0e9, -6360000.0};
  Camera c;
  c.position_m = {1.0e9, -2.0e9, 100.0};
  FrameBlock u = make_uniforms(a, nullptr, nullptr, make_frame_view(c, 16, 16));
  EXPECT_NEAR(u.camera_km.z, 6360.1, 1e-3);
  EXPECT_NEAR(u.camera_km.x, 0.0, 1e-6);
  EXPECT_EQ(u.camera_in_space, 0.0f);  // inside the atmosphere
}

TEST(AtmosphereUniforms, CameraUnderGroundIsLiftedAndSpaceIsDetected) {
  Atmosphere a;
  Camera c;
  c.position_m = {0, 0, -5000};
  FrameBlock u = make_uniforms(a, nullptr, nullptr, make_frame_view(c, 16, 16));
  EXPECT_GT(u.camera_radius_km, a.bottom_radius_km);
  c.position_m = {0, 0, 400000};
  u = make_uniforms(a, nullptr, nullptr, make_frame_view(c, 16, 16));
  EXPECT_EQ(u.camera_in_space, 1.0f);
}

TEST(AtmosphereUniforms, QualityPresetsAndCustom) {
  Atmosphere a;
  a.quality = Quality::low;
  EXPECT_LT(resolve_quality(a).transmittance_width, 256);
  a.quality = Quality::custom;
  a.transmittance_width = 7;
  EXPECT_EQ(resolve_quality(a).transmittance_width, 7);
  a.quality = Quality::high;
  ResolvedQuality q = resolve_quality(a);
  EXPECT_EQ(q.transmittance_width, 256);
  EXPECT_EQ(q.multiscattering_size, 48);
  EXPECT_EQ(q.sky_view_width, 192);
  EXPECT_EQ(q.aerial_perspective_slices, 32);
}

using welkin::testing::CacheFolder;

TEST(AtmosphereLuts, RegeneratedOnlyWhenTheMediumChanges) {
  const CacheFolder no_cache("");
  auto r = test::render(test::scene(json::object(), json::object()), 16, 8, 3);
  EXPECT_EQ(r.gpu().lut_builds, 1);
  auto has_pass = [&](const std::string& name) {
    for (const auto& t : r.last.timings)
      if (t.name == name) return true;
    return false;
  };
  EXPECT_FALSE(has_pass("atmosphere.transmittance"));
  Registry& reg = r.world->registry();
  reg.get<Sun>(reg.first<Sun>())->elevation_deg = 3.0f;  // the sun is not part of the medium
  reg.get<Camera>(reg.first<Camera>())->position_m.z = 3000.0;
  r.frame(16, 8, 3);
  EXPECT_EQ(r.gpu().lut_builds, 1);
  reg.get<Atmosphere>(reg.first<Atmosphere>())->mie_g = 0.7f;
  r.frame(16, 8, 4);
  EXPECT_EQ(r.gpu().lut_builds, 2);
  EXPECT_TRUE(has_pass("atmosphere.multiscattering"));
}

// A start with the disk cache (core/disk_cache.h) reads the persistent LUTs a start before built,
// bit for bit, and draws the same frame; another medium is a miss and is built.
TEST(AtmosphereLuts, ReadFromTheDiskCacheBitForBit) {
  const std::filesystem::path dir =
      welkin::testing::scratch_folder("welkin-lut-cache") / "cache";
  std::filesystem::remove_all(dir);
  const CacheFolder cache(dir.string());
  const json sun = {{"elevation_deg", -4}};
  auto built = test::render(test::scene(json::object(), json::object(), sun), 16, 8);
  EXPECT_EQ(built.gpu().lut_builds, 1);
  EXPECT_EQ(built.gpu().lut_cache_reads, 0);
  ASSERT_TRUE(std::filesystem::exists(dir));
  auto read = test::render(test::scene(json::object(), json::object(), sun), 16, 8);
  EXPECT_EQ(read.gpu().lut_builds, 0);
  EXPECT_EQ(read.gpu().lut_cache_reads, 1);
  for (auto lut : {&AtmosphereGpu::transmittance, &AtmosphereGpu::multiscattering})
    EXPECT_EQ(read_texture_float(*(read.gpu().*lut)).rgba, read_texture_float(*(built.gpu().*lut)).rgba);
  EXPECT_EQ(read.renderer->read_hdr().rgba, built.renderer->read_hdr().rgba);
  for (const auto& t : read.last.timings) EXPECT_NE(t.name, "atmosphere.multiscattering");
  auto other = test::render(test::scene(json::object(), {{"mie_g", 0.7}}, sun), 16, 8);
  EXPECT_EQ(other.gpu().lut_builds, 1);
  EXPECT_EQ(other.gpu().lut_cache_reads, 0);
  std::filesystem::remove_all(dir);
}

// The per-frame LUTs are kept while what they depend on holds still, and the frame drawn from kept
// LUTs is the frame drawn from fresh ones, bit for bit: turning the camera keeps the sky-view LUT
// (laid out around the camera's position and the sun) and rebuilds the aerial-perspective volume
// (it follows the view); moving the sun rebuilds both.
TEST(AtmosphereLuts, PerFrameLutsAreKeptWhileTheirInputsHoldStill) {
  const json sun = {{"azimuth_deg", 120}, {"elevation_deg", 20}};
  auto doc = [&](double heading, double elevation) {
    json s = sun;
    s["elevation_deg"] = elevation;
    return test::scene({{"position_m", {0, 0, 200}}, {"heading_deg", heading}, {"pitch_deg", 5}}, json::object(), s);
  };
  auto kept = test::render(doc(0, 20), 16, 8, 3);
  EXPECT_EQ(kept.gpu().sky_view_builds, 1);
  EXPECT_EQ(kept.gpu().aerial_builds, 1);
  auto same_image = [&](double heading, double elevation) {
    auto fresh = test::render(doc(heading, elevation), 16, 8, 1);
    return kept.renderer->read_hdr().rgba == fresh.renderer->read_hdr().rgba;
  };
  EXPECT_TRUE(same_image(0, 20));
  Registry& reg = kept.world->registry();
  reg.get<Camera>(reg.first<Camera>())->heading_deg = 40.0;
  kept.frame(16, 8, 3);
  EXPECT_EQ(kept.gpu().sky_view_builds, 1);
  EXPECT_EQ(kept.gpu().aerial_builds, 2);
  EXPECT_TRUE(same_image(40, 20));
  reg.get<Sun>(reg.first<Sun>())->elevation_deg = 21.0f;
  kept.frame(16, 8, 4);
  EXPECT_EQ(kept.gpu().sky_view_builds, 2);
  EXPECT_EQ(kept.gpu().aerial_builds, 3);
  EXPECT_TRUE(same_image(40, 21));
  EXPECT_FALSE(same_image(40, 20));  // the comparison can fail
}

TEST(AtmosphereFrame, PassesAndBlackboard) {
  const CacheFolder no_cache("");
  auto r = test::render(test::scene(json::object(), json::object()), 16, 8);
  std::vector<std::string> names;
  for (const auto& t : r.last.timings) names.push_back(t.name);
  for (const char* p : {"atmosphere.transmittance", "atmosphere.multiscattering", "atmosphere.sky_view",
                        "atmosphere.aerial_perspective", "atmosphere.sky_irradiance", "atmosphere.sky"})
    EXPECT_NE(std::find(names.begin(), names.end(), p), names.end()) << p;
  EXPECT_TRUE(r.last.culled_passes.empty());
  // The aerial perspective is applied where geometry is, and not at all without any.
  const char* apply = "atmosphere.aerial_perspective_apply";
  EXPECT_EQ(std::find(names.begin(), names.end(), apply), names.end());
  json doc = test::scene(json::object(), json::object());
  doc["entities"].push_back({{"name", "ball"}, {"components", {{"core.DebugShape", {{"position_m", {0, 30, 2}}}}}}});
  auto with_geometry = test::render(doc, 16, 8);
  names.clear();
  for (const auto& t : with_geometry.last.timings) names.push_back(t.name);
  EXPECT_NE(std::find(names.begin(), names.end(), apply), names.end());
}

TEST(AtmosphereFrame, SameImageWhereverThePlanetIs) {
  // Camera-relative rendering: moving camera and planet 1000 km across the scene frame changes
  // nothing on screen.
  json cam = {{"position_m", {0, 0, 2}}, {"pitch_deg", 10}};
  json far_cam = {{"position_m", {1.0e6, -1.0e6, 2}}, {"pitch_deg", 10}};
  json far_atm = {{"planet_center_below_origin", false}, {"planet_center_m", {1.0e6, -1.0e6, -6360000}}};
  auto a = test::render(test::scene(cam, json::object()), 32, 16);
  auto b = test::render(test::scene(far_cam, far_atm), 32, 16);
  ImageF ia = a.renderer->read_hdr(), ib = b.renderer->read_hdr();
  double worst = 0;
  for (size_t i = 0; i < ia.rgba.size(); ++i)
    worst = std::max(worst, std::abs(double(ia.rgba[i]) - ib.rgba[i]) / std::max(1.0, double(ia.rgba[i])));
  EXPECT_LT(worst, 1e-3);
}

TEST(AtmosphereFrame, SkyBehavesPhysically) {
  // Noon: the high sky is blue and darker than the horizon. Sunset: the sky around the low sun turns
  // red. Images 9 x 33 with a 150-degree vertical field: row 16 is the horizon, row 0 is 75 deg up.
  auto look = [](double sun_elevation) {
    auto r = test::render(
        test::scene({{"pitch_deg", 0}, {"vertical_fov_deg", 150}, {"heading_deg", 0}}, json::object(),
                    {{"elevation_deg", sun_elevation}, {"azimuth_deg", 0}, {"disc", false}}),
        9, 33);
    return r.renderer->read_hdr();
  };
  ImageF noon = look(60), sunset = look(1);
  const float* high = noon.pixel(4, 0);
  const float* horizon = noon.pixel(4, 15);
  EXPECT_GT(high[2], high[0] * 2.0f);
  EXPECT_GT(horizon[1], high[1]);
  const float* low_sun = sunset.pixel(4, 15);
  EXPECT_GT(low_sun[0] / low_sun[2], 2.0f * horizon[0] / horizon[2]);
}

}  // namespace
}  // namespace welkin::atmosphere

namespace welkin::atmosphere {
namespace {

TEST(AtmosphereUniforms, MoonLightsTheSkyOnlyWhereItCanShow) {
  Atmosphere a;
  Camera c;
  c.position_m = {0, 0, 2};
  const FrameView view = make_frame_view(c, 16, 16);
  Sun sun;
  Moon moon;
  sun.elevation_deg = -20.0f;
  EXPECT_EQ(make_uniforms(a, &sun, &moon, view).moon_lights_sky, 1.0f) << "night";
  sun.elevation_deg = 0.5f;
  EXPECT_EQ(make_uniforms(a, &sun, &moon, view).moon_lights_sky, 0.0f) << "day";
  // A moon bright against its sun (another planet's, or an artist's) keeps its light.
  sun.illuminance_lux = 10000.0f;
  moon.illuminance_lux = 100.0f;
  EXPECT_EQ(make_uniforms(a, &sun, &moon, view).moon_lights_sky, 1.0f) << "bright moon";
  // From space the planet's night side is in view whatever the sun does.
  sun.illuminance_lux = 120000.0f;
  moon.illuminance_lux = 0.25f;
  c.position_m = {0, 0, 400000};
  EXPECT_EQ(make_uniforms(a, &sun, &moon, make_frame_view(c, 16, 16)).moon_lights_sky, 1.0f) << "space";
}

TEST(AtmosphereFrame, DaylightDrownsTheFullMoonsSky) {
  // The premise of leaving moonlight out by day: at the lowest sun that does so (just above the
  // horizon), the sky a full moon high in the sky lights is below 1/1000 of the sun's, everywhere.
  auto sky = [](double sun_elevation, const json* moon) {
    auto r = test::render(
        test::scene({{"pitch_deg", 0}, {"vertical_fov_deg", 150}, {"heading_deg", 180}}, json::object(),
                    {{"elevation_deg", sun_elevation}, {"azimuth_deg", 0}, {"disc", false}}, moon),
        9, 33);
    return r.renderer->read_hdr();
  };
  const json full_moon = {{"elevation_deg", 60}, {"azimuth_deg", 180}, {"illuminance_lux", 0.3}, {"disc", false}};
  const ImageF by_sun = sky(0.1, nullptr), by_moon = sky(-90, &full_moon);
  double worst = 0.0;
  for (int y = 0; y < 17; ++y)  // the sky rows, zenith-ward of the horizon
    for (int x = 0; x < 9; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_GT(by_sun.pixel(x, y)[ch], 0.0f);
        worst = std::max(worst, double(by_moon.pixel(x, y)[ch]) / by_sun.pixel(x, y)[ch]);
      }
  std::printf("moonlit sky / sunlit sky, worst pixel: %.2e\n", worst);
  EXPECT_GT(worst, 0.0);
  EXPECT_LT(worst, 1e-3);
}

// The sky is drawn again only when something it is drawn from changed; a kept sky is the sky a
// fresh world draws, bit for bit, and turning the camera or the sun draws it again.
TEST(AtmosphereFrame, SkyIsKeptWhileItsInputsAreTheSame) {
  auto doc = [](double heading, double sun_elevation) {
    return test::scene({{"heading_deg", heading}, {"pitch_deg", 10}}, json::object(),
                       {{"elevation_deg", sun_elevation}, {"azimuth_deg", 120}});
  };
  auto fresh = [&](double heading, double sun_elevation) {
    return test::render(doc(heading, sun_elevation), 32, 18).renderer->read_hdr().rgba;
  };
  test::Rendered r = test::render(doc(0, 30), 32, 18, 5);
  // The first frame draws; the second too (the sky-view LUT was built during the first), the third
  // draws alike and keeps it; the rest copy it.
  EXPECT_EQ(r.gpu().sky_draws, 3);
  EXPECT_EQ(r.renderer->read_hdr().rgba, fresh(0, 30));
  Registry& reg = r.world->registry();
  reg.get<Camera>(reg.first<Camera>())->heading_deg = 40;
  r.frame(32, 18);
  EXPECT_EQ(r.gpu().sky_draws, 4) << "the camera turned";
  EXPECT_EQ(r.renderer->read_hdr().rgba, fresh(40, 30));
  r.frame(32, 18);
  r.frame(32, 18);
  r.frame(32, 18);
  EXPECT_EQ(r.gpu().sky_draws, 5) << "the sky-view LUT is laid out around the camera's position: kept";
  reg.get<Sun>(reg.first<Sun>())->elevation_deg = 20;
  r.frame(32, 18);
  EXPECT_EQ(r.gpu().sky_draws, 6) << "the sun moved";
  for (int i = 0; i < 4; ++i) r.frame(32, 18);
  EXPECT_EQ(r.gpu().sky_draws, 8) << "again after the sky-view LUT was built, then kept";
  EXPECT_EQ(r.renderer->read_hdr().rgba, fresh(40, 20));
  // A benchmark of the per-frame cost forgets it with the per-frame LUTs.
  const int draws = r.gpu().sky_draws;
  r.gpu().forget_per_frame_luts();
  r.frame(32, 18);
  EXPECT_EQ(r.gpu().sky_draws, draws + 1);
}

// A camera turning in place keeps its aerial-perspective volume while the view stays inside the
// volume's frustum, which is made wider than the view (kAerialTurningMargin) once it turns: made one
// frame in several instead of every frame. A frame drawn through a kept volume differs from one drawn
// afresh only by where the volume's columns fall (measured); a view that stops turning gets a volume
// fitted to it again, and with it the fresh frame bit for bit. A camera that moves remakes it.
TEST(AtmosphereFrame, AerialPerspectiveKeptWhileTheViewTurnsInsideItsVolume) {
  auto doc = [](double heading, double x) {
    json d = test::scene({{"position_m", {x, 0, 30}}, {"heading_deg", heading}, {"pitch_deg", -5}, {"vertical_fov_deg", 50}},
                         json::object(), {{"elevation_deg", 20}, {"azimuth_deg", 120}});
    // A ground 60 km wide below the camera: aerial perspective from a few metres to the haze.
    d["entities"].push_back({{"name", "ground"},
                             {"components", {{"core.DebugShape", {{"shape", "box"}, {"position_m", {0, 0, -1}},
                                                                  {"size_m", {60000, 60000, 2}}, {"albedo", {0.2, 0.25, 0.15}}}}}}});
    return d;
  };
  constexpr int kW = 64, kH = 36;
  auto fresh = [&](double heading, double x = 0.0) { return test::render(doc(heading, x), kW, kH).renderer->read_hdr().rgba; };
  test::Rendered r = test::render(doc(0, 0), kW, kH, 2);
  EXPECT_EQ(r.gpu().aerial_builds, 1);
  Registry& reg = r.world->registry();
  Camera& camera = *reg.get<Camera>(reg.first<Camera>());
  double worst = 0.0;
  for (int turn = 1; turn <= 18; ++turn) {
    camera.heading_deg = float(turn);
    r.frame(kW, kH, uint64_t(turn + 1));
    if (turn % 6 == 3) {
      const std::vector<float> kept = r.renderer->read_hdr().rgba, drawn = fresh(turn);
      for (size_t i = 0; i < kept.size(); ++i)
        if (i % 4 != 3) worst = std::max(worst, std::abs(double(kept[i]) - drawn[i]) / std::max(1e-3, double(drawn[i])));
    }
  }
  const int turning_builds = r.gpu().aerial_builds - 1;
  std::printf("18 frames turning 1 degree each: %d volumes made; worst relative difference to fresh frames %.2e\n",
              turning_builds, worst);
  EXPECT_LE(turning_builds, 6) << "one volume per several frames";
  EXPECT_GE(turning_builds, 2) << "each covers a few degrees only";
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(worst, 0.0) << "the kept volume's columns are not the fresh one's";
  // The turn stops: one volume fitted to the view, then kept; the frame is the fresh one.
  const int before_stop = r.gpu().aerial_builds;
  r.frame(kW, kH, 100);
  r.frame(kW, kH, 101);
  EXPECT_EQ(r.gpu().aerial_builds, before_stop + 1);
  EXPECT_EQ(r.renderer->read_hdr().rgba, fresh(18));
  // A moving camera remakes it every frame, fitted to its view.
  for (int step = 1; step <= 3; ++step) {
    camera.position_m.x = 10.0 * step;
    r.frame(kW, kH, uint64_t(101 + step));
  }
  EXPECT_EQ(r.gpu().aerial_builds, before_stop + 4);
  EXPECT_EQ(r.renderer->read_hdr().rgba, fresh(18, 30.0));
}

TEST(AtmosphereFrame, DaylightDrownsTheFullMoonsLightOnSurfaces) {
  // Materials leave the moon out wherever it does not light the sky. The worst case by day: a sun
  // just above the horizon behind a grey ball, a full moon 30 degrees up behind the camera, the
  // face seen lit by the sky alone; the moon's light on that face (moon alone, sun far below) must
  // stay below 1/1000 of it.
  const json ball = {{"name", "ball"},
                     {"components", {{"core.DebugShape", {{"shape", "sphere"}, {"position_m", {0, 20, 2}},
                                                          {"size_m", {10, 10, 10}}, {"albedo", {0.5, 0.5, 0.5}}}}}}};
  const json full_moon = {{"elevation_deg", 30}, {"azimuth_deg", 180}, {"illuminance_lux", 0.3}, {"disc", false}};
  auto face = [&](double sun_elevation, const json* moon, bool moon_in_materials) {
    json doc = test::scene({{"position_m", {0, 0, 2}}, {"pitch_deg", 0}, {"vertical_fov_deg", 10}}, json::object(),
                           {{"elevation_deg", sun_elevation}, {"azimuth_deg", 0}, {"disc", false}}, moon);
    doc["entities"].push_back(ball);
    auto r = test::render(doc, 8, 8);
    EXPECT_EQ(r.world->resource<LightEnvironment>().moon_lights_surfaces(), moon_in_materials)
        << "sun at " << sun_elevation << (moon ? " with a moon" : "");
    return r.renderer->read_hdr();
  };
  const ImageF by_sun = face(0.1, nullptr, false), by_moon = face(-90, &full_moon, true);
  face(0.1, &full_moon, false);
  double worst = 0.0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_GT(by_sun.pixel(x, y)[ch], 0.0f);
        worst = std::max(worst, double(by_moon.pixel(x, y)[ch]) / by_sun.pixel(x, y)[ch]);
      }
  std::printf("moonlit face / sunlit face, worst pixel: %.2e\n", worst);
  EXPECT_LT(worst, 1e-3);
  // At night the moon is in the material: its direct light (0.3 lx at 60 degrees from the face's
  // normal, some of it lost in the air) is most of the face's; the moonlit sky alone gives a tenth.
  const double direct = 0.5 / M_PI * 0.3 * std::cos(glm::radians(30.0));
  EXPECT_GT(by_moon.pixel(4, 4)[1], 0.5 * direct);
  EXPECT_LT(by_moon.pixel(4, 4)[1], 1.3 * direct);
}

}  // namespace
}  // namespace welkin::atmosphere
