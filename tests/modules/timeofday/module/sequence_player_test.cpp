#include "welkin/scene/sequence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/scene_file.h"
#include "welkin/timeofday/components.h"
#include "scratch_folder.h"

namespace welkin::modules {
const ModuleDefinition& timeofday_module();
}

namespace {

using namespace welkin;
using namespace welkin::timeofday;
using welkin::Track; using welkin::Keyframe; using welkin::Interpolation; using welkin::Easing;
using nlohmann::json;

Track track(Interpolation in, std::vector<std::pair<double, double>> keys, double wrap = 0) {
  Track t;
  t.interpolation = in;
  t.wrap = wrap;
  for (auto [time, v] : keys) t.keys.push_back(Keyframe{.t = time, .value = {v}});
  return t;
}

TEST(Sequence, InterpolationMatchesClosedForms) {
  EXPECT_DOUBLE_EQ(evaluate_track(track(Interpolation::linear, {{0, 2}, {4, 10}}), 1)[0], 4.0);
  EXPECT_DOUBLE_EQ(evaluate_track(track(Interpolation::step, {{0, 2}, {4, 10}}), 3.99)[0], 2.0);
  EXPECT_DOUBLE_EQ(evaluate_track(track(Interpolation::smooth, {{0, 0}, {2, 1}}), 0.5)[0], 0.15625);  // u=1/4: 3u^2-2u^3
  EXPECT_DOUBLE_EQ(evaluate_track(track(Interpolation::linear, {{0, 2}, {4, 10}}), -1)[0], 2.0) << "clamped before";
  EXPECT_DOUBLE_EQ(evaluate_track(track(Interpolation::linear, {{0, 2}, {4, 10}}), 9)[0], 10.0) << "clamped after";
  // Cubic Hermite with Catmull-Rom tangents reproduces any line exactly, even with uneven keys.
  Track line = track(Interpolation::cubic, {{0, 1}, {1, 3}, {3.5, 8}, {4, 9}});
  for (double t = 0; t <= 4; t += 0.37) EXPECT_NEAR(evaluate_track(line, t)[0], 1 + 2 * t, 1e-12) << t;
  // ...and passes through every key.
  Track wiggle = track(Interpolation::cubic, {{0, 0}, {1, 5}, {2, -3}, {3, 4}});
  for (const auto& k : wiggle.keys) EXPECT_NEAR(evaluate_track(wiggle, k.t)[0], k.value[0], 1e-12);
}

TEST(Sequence, EasingShapesTheSegmentEndingAtTheKey) {
  Track t = track(Interpolation::linear, {{0, 0}, {1, 1}});
  t.keys[1].easing = Easing::ease_in;
  EXPECT_DOUBLE_EQ(evaluate_track(t, 0.5)[0], 0.25);
  t.keys[1].easing = Easing::ease_out;
  EXPECT_DOUBLE_EQ(evaluate_track(t, 0.5)[0], 0.75);
}

TEST(Sequence, WrappingCrossesMidnightAnd360TheShortWay) {
  Track clock = track(Interpolation::linear, {{0, 23.0}, {2, 1.0}}, 24);
  EXPECT_NEAR(evaluate_track(clock, 1)[0], 0.0, 1e-12);
  EXPECT_NEAR(evaluate_track(clock, 0.5)[0], 23.5, 1e-12);
  EXPECT_NEAR(evaluate_track(clock, 1.5)[0], 0.5, 1e-12);
  Track heading = track(Interpolation::smooth, {{0, 350.0}, {1, 10.0}}, 360);
  EXPECT_NEAR(evaluate_track(heading, 0.5)[0], 0.0, 1e-12);
  for (double t = 0; t <= 1; t += 0.05) {
    double v = evaluate_track(heading, t)[0];
    EXPECT_TRUE(v >= 350 - 1e-9 || v <= 10 + 1e-9) << "never the long way round: " << v;
  }
}

std::string error_of(const std::string& text) {
  try {
    parse_sequence(json::parse(text), "seq.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Sequence, BadInputNamesFileAndPath) {
  auto head = std::string(R"({"welkin_sequence": 1, "tracks": [{"target": "timeofday.TimeOfDay/local_time_h", )");
  EXPECT_NE(error_of(head + R"("keys": [{"t": 2, "value": 1}, {"t": 1, "value": 2}]}]})").find("seq.json: at /tracks/0/keys/1/t: keyframes out of order"), std::string::npos);
  EXPECT_NE(error_of(head + R"("keys": []}]})").find("at /tracks/0/keys: empty track"), std::string::npos);
  EXPECT_NE(error_of(head + R"("keys": [{"t": 0, "value": "noon"}]}]})").find("/tracks/0/interpolation"), std::string::npos);
  EXPECT_NE(error_of(head + R"("keys": [{"t": 0, "value": [1, 2]}, {"t": 1, "value": [1]}]}]})").find("/tracks/0/keys/1/value"), std::string::npos);
  EXPECT_NE(error_of(head + R"("keys": [{"t": 0, "value": {}}]}]})").find("/tracks/0/keys/0/value"), std::string::npos);
  EXPECT_NE(error_of(head + R"("interpolation": "bezier", "keys": [{"t": 0, "value": 1}]}]})").find("\"step\", \"linear\", \"smooth\", \"cubic\""), std::string::npos);
  EXPECT_NE(error_of(head + R"("keyz": []}]})").find("/tracks/0/keyz: unknown key"), std::string::npos);
  EXPECT_NE(error_of(R"({"welkin_sequence": 1, "tracks": [{"target": "nofield", "keys": [{"t": 0, "value": 1}]}]})").find("/tracks/0/target"), std::string::npos);
  EXPECT_NE(error_of(R"({"tracks": []})").find("/welkin_sequence"), std::string::npos);
}

struct Scene {
  std::unique_ptr<World> world = std::make_unique<World>();
  Scene() {
    world->modules().add_static(modules::timeofday_module());
    load_scene_file(*world, WELKIN_SOURCE_DIR "/assets/scenes/debug.json");
    json tod{{"welkin_scene", 1}, {"entities", json::array({json{{"components", {{"timeofday.TimeOfDay", {{"time_scale", 60}}}}}}})}};
    load_scene(*world, tod, "tod.json");
  }
  json state() const { return save_scene(*world); }
};

TEST(Sequence, ScrubbingGivesTheSameStateAsPlaying) {
  const std::string file = WELKIN_SOURCE_DIR "/assets/sequences/dawn-to-noon.json";
  Scene played, scrubbed;
  Entity pp = played.world->registry().create();
  played.world->registry().emplace<SequencePlayer>(pp).file = file;
  for (int i = 0; i < 250; ++i) played.world->update({.dt_s = 0.04});  // 10 s of sequence time
  Entity sp = scrubbed.world->registry().create();
  auto& p = scrubbed.world->registry().emplace<SequencePlayer>(sp);
  p.file = file;
  p.playing = false;
  p.time_s = 40.0;  // somewhere else first
  scrubbed.world->update({});
  p.time_s = played.world->registry().get<SequencePlayer>(pp)->time_s;
  EXPECT_NEAR(p.time_s, 10.0, 1e-9);
  scrubbed.world->update({});
  p.playing = true;  // the only intended difference between the two players
  EXPECT_EQ(scrubbed.state(), played.state());
  auto* cam = played.world->registry().get<Camera>(played.world->registry().first<Camera>());
  EXPECT_NE(cam->position_m.z, 2.0) << "the camera track moved the camera";
}

TEST(Sequence, UnknownTargetIsAnErrorUnlessOptional) {
  const auto& dir = welkin::testing::scratch_folder("welkin-sequence-test");
  auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  std::string bad = write("welkin-seq-bad.json", R"({"welkin_sequence": 1, "tracks": [
    {"target": "timeofday.TimeOfDay/local_time_h", "keys": [{"t": 0, "value": 6}]},
    {"target": "clouds.VolumetricClouds/coverage", "keys": [{"t": 0, "value": 0.5}]}]})");
  Scene s;
  Entity e = s.world->registry().create();
  s.world->registry().emplace<SequencePlayer>(e).file = bad;
  try {
    s.world->update({});
    FAIL();
  } catch (const Error& err) {
    std::string m = err.what();
    EXPECT_NE(m.find(bad + ": at /tracks/1/target"), std::string::npos) << m;
    EXPECT_NE(m.find("clouds"), std::string::npos) << m;
  }
  std::string ok = write("welkin-seq-ok.json", R"({"welkin_sequence": 1, "tracks": [
    {"target": "timeofday.TimeOfDay/local_time_h", "keys": [{"t": 0, "value": 6}]},
    {"target": "clouds.VolumetricClouds/coverage", "optional": true, "keys": [{"t": 0, "value": 0.5}]}]})");
  s.world->registry().get<SequencePlayer>(e)->file = ok;
  s.world->update({});
  EXPECT_EQ(s.world->registry().get<TimeOfDay>(s.world->registry().first<TimeOfDay>())->local_time_h, 6.0);
}

}  // namespace
