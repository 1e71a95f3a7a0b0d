// The timeline: key edits are undoable document edits, tracks interpolate through the target
// field's reflection, and sequence files round-trip and reject bad input with a path.
#include "model/sequence.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "model/editor_document.h"
#include "test_module.h"
#include "welkin/core/error.h"

namespace {

using namespace welkin;
using namespace welkin::editor;
// The editor's timeline document, not the runtime's welkin::Sequence that it converts to.
using welkin::editor::Keyframe;
using welkin::editor::Sequence;
using welkin::editor::load_sequence_file;
using editor_test::ScratchDir;
using nlohmann::json;

const char* kDebugScene = WELKIN_SOURCE_DIR "/assets/scenes/debug.json";
const std::string kElevation = "core.DirectionalLight/elevation_deg";

TEST(Sequence, WithKeyKeepsKeysSortedAndReplacesSameTime) {
  Sequence s;
  s = with_key(s, "sun", kElevation, 10, 5);
  s = with_key(s, "sun", kElevation, 0, -5);
  s = with_key(s, "sun", kElevation, 10, 7);
  ASSERT_EQ(s.tracks.size(), 1u);
  ASSERT_EQ(s.tracks[0].keys.size(), 2u);
  EXPECT_EQ(s.tracks[0].keys[0], (Keyframe{0, -5}));
  EXPECT_EQ(s.tracks[0].keys[1], (Keyframe{10, 7}));
  s = with_key_moved(s, "sun", kElevation, 10, 20);
  EXPECT_EQ(s.tracks[0].keys[1], (Keyframe{20, 7}));
  s = without_key(s, "sun", kElevation, 0);
  s = without_key(s, "sun", kElevation, 20);
  EXPECT_TRUE(s.tracks.empty());
}

TEST(Sequence, FileRoundTripsAndIsWrittenAtomically) {
  ScratchDir dir("sequence");
  Sequence s;
  s.duration_s = 90;
  s = with_key(s, "sun", kElevation, 0, -5);
  s = with_key(s, "", "core.Backdrop/zenith_color", 45, json::parse("[0.1, 0.2, 0.3]"));
  auto path = (dir.path() / "day.json").string();
  save_sequence_file(path, s);
  EXPECT_EQ(load_sequence_file(path), s);
}

TEST(Sequence, BadDocumentsNameThePath) {
  auto path_of = [](const char* text) {
    try {
      sequence_from_json(json::parse(text), "seq.json");
    } catch (const Error& e) {
      EXPECT_EQ(e.info().file, "seq.json");
      return e.info().path;
    }
    return std::string("accepted");
  };
  EXPECT_EQ(path_of(R"({"welkin_sequence": 2})"), "/welkin_sequence");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "nocomponent", "keys": []}]})"), "/tracks/0/target");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": [{"t": 5, "value": 1}, {"t": 2, "value": 1}]}]})"),
            "/tracks/0/keys/1/t");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": [{"t": -1, "value": 1}]}]})"),
            "/tracks/0/keys/0/t");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": [{"t": 0, "value": "x"}]}]})"),
            "/tracks/0/interpolation");  // names must step
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": [{"t": 0, "value": 1}, {"t": 1, "value": [1, 2]}]}]})"),
            "/tracks/0/keys/1/value");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": [{"t": 0, "value": 1, "easing": "bouncy"}]}]})"),
            "/tracks/0/keys/0/easing");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "tracks": [{"target": "a.B/c", "keys": []}]})"), "/tracks/0/keys");
  EXPECT_EQ(path_of(R"({"welkin_sequence": 1, "speed": 2})"), "/speed");
}

TEST(Sequence, TheShippedSequencesLoadAndRoundTripWithEveryAttribute) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(WELKIN_SOURCE_DIR "/assets/sequences")) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    Sequence s = load_sequence_file(entry.path().string());
    EXPECT_FALSE(s.tracks.empty()) << entry.path();
    EXPECT_EQ(sequence_from_json(sequence_to_json(s), "again"), s) << entry.path();
  }
  EXPECT_GE(files, 1);
  Sequence dawn = load_sequence_file(WELKIN_SOURCE_DIR "/assets/sequences/dawn-to-noon.json");
  EXPECT_FALSE(dawn.description.empty());
  EXPECT_EQ(dawn.tracks[0].interpolation, Interpolation::cubic);
  EXPECT_EQ(dawn.tracks[0].wrap, 24.0);
}

SequenceTrack track_of(Interpolation interpolation, std::vector<Keyframe> keys, double wrap = 0) {
  return SequenceTrack{.target = "a.B/c", .interpolation = interpolation, .wrap = wrap, .keys = std::move(keys)};
}

TEST(Sequence, EvaluationFollowsTheTimeofdayCurves) {
  // The curves are welkin::evaluate_track's (the runtime's, formerly the timeofday module's); these
  // pin them to closed-form values.
  // Linear, clamped at both ends.
  auto lin = track_of(Interpolation::linear, {{0, 10}, {10, 20}});
  EXPECT_EQ(evaluate_track_value(lin, -1), json(10));
  EXPECT_EQ(evaluate_track_value(lin, 2.5), json(12.5));
  EXPECT_EQ(evaluate_track_value(lin, 99), json(20));
  // Smoothstep: equal at the midpoint, slower at the ends.
  auto smooth = track_of(Interpolation::smooth, {{0, 0}, {10, 1}});
  EXPECT_DOUBLE_EQ(evaluate_track_value(smooth, 5).get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(evaluate_track_value(smooth, 2.5).get<double>(), 0.15625);  // 3u^2 - 2u^3 at 0.25
  // Easing of the segment's end key: ease_in at u = 0.5 is 0.25.
  auto eased = track_of(Interpolation::linear, {{0, 0}, {10, 8, Easing::ease_in}});
  EXPECT_DOUBLE_EQ(evaluate_track_value(eased, 5).get<double>(), 2.0);
  // Wrapping crosses midnight the short way: 23.5 h -> 0.5 h passes 0, not noon.
  auto clock = track_of(Interpolation::linear, {{0, 23.5}, {10, 0.5}}, 24);
  EXPECT_DOUBLE_EQ(evaluate_track_value(clock, 5).get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(evaluate_track_value(clock, 2.5).get<double>(), 23.75);
  // Cubic passes through its keys; vectors interpolate per component; names step.
  auto cubic = track_of(Interpolation::cubic, {{0, json::array({0, 0})}, {4, json::array({4, 8})}, {6, json::array({0, 2})}});
  EXPECT_EQ(evaluate_track_value(cubic, 4), json::array({4, 8}));
  auto names = track_of(Interpolation::step, {{0, "sphere"}, {1, "box"}});
  EXPECT_EQ(evaluate_track_value(names, 0.99), json("sphere"));
}

class Timeline : public ::testing::Test {
 protected:
  Timeline() : doc(editor_test::make_test_world) { doc.load_scene(kDebugScene); }
  EditorDocument doc;
};

TEST_F(Timeline, KeyEditsUndoAndRedo) {
  doc.set_sequence(with_key(doc.sequence(), "sun", kElevation, 0, -5), "key");
  doc.set_sequence(with_key(doc.sequence(), "sun", kElevation, 60, 40), "key");
  EXPECT_EQ(doc.sequence().tracks[0].keys.size(), 2u);
  doc.undo();
  EXPECT_EQ(doc.sequence().tracks[0].keys.size(), 1u);
  doc.undo();
  EXPECT_TRUE(doc.sequence().tracks.empty());
  doc.redo();
  doc.redo();
  EXPECT_EQ(doc.sequence().tracks[0].keys[1], (Keyframe{60, 40}));
}

TEST_F(Timeline, PreviewInterpolatesNumbersAndHoldsEnds) {
  Sequence s = with_key({}, "sun", kElevation, 0, -5);
  s = with_key(s, "sun", kElevation, 40, 35);
  s = with_key(s, "ball", "core.DebugShape/shape", 0, "sphere");
  s = with_key(s, "ball", "core.DebugShape/shape", 10, "box");
  s = with_key(s, "ball", "core.DebugShape/albedo/1", 0, 0.0);
  s = with_key(s, "ball", "core.DebugShape/albedo/1", 10, 1.0);
  doc.set_sequence(s, "keys");
  EntityId sun = doc.find_by_name("sun"), ball = doc.find_by_name("ball");
  EXPECT_TRUE(doc.preview_sequence(10).empty());
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), json(5));
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "shape"), json("box"));  // past the halfway switch
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "albedo/1"), json(1.0));
  doc.preview_sequence(2.5);
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "shape"), json("sphere"));
  EXPECT_EQ(doc.get_field(ball, "core.DebugShape", "albedo/1"), json(0.25));
  doc.preview_sequence(100);
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), json(35));
  EXPECT_FALSE(doc.history().steps().size() > 1);  // previews are not edits
}

// The preview writes over the scene for the view only: a save writes the scene's own values, an
// edit's undo step holds them, and the scene is not dirtied (editor/README.md, "Timeline").
TEST_F(Timeline, PreviewNeverReachesTheDocument) {
  ScratchDir dir("timeline-preview");
  EntityId sun = doc.find_by_name("sun");
  const json own = doc.get_field(sun, "core.DirectionalLight", "elevation_deg");
  doc.set_sequence(with_key(with_key({}, "sun", kElevation, 0, -5), "sun", kElevation, 40, 35), "keys");
  const auto path = (dir.path() / "scene.json").string();
  doc.save_scene(path);
  ASSERT_FALSE(doc.scene_dirty());

  doc.preview_sequence(40);
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), json(35));
  EXPECT_TRUE(doc.previewing());
  EXPECT_FALSE(doc.scene_dirty());

  doc.save_scene(path);  // writes the scene's own elevation, not the playhead's
  EXPECT_FALSE(doc.previewing());
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), own);
  EntityId reloaded = kNoEntity;
  {
    EditorDocument other(editor_test::make_test_world);
    other.load_scene(path);
    reloaded = other.find_by_name("sun");
    EXPECT_EQ(other.get_field(reloaded, "core.DirectionalLight", "elevation_deg"), own);
  }

  // An edit during a preview: its undo goes back to the scene's own value, not the previewed one.
  doc.preview_sequence(40);
  doc.set_field(sun, "core.DirectionalLight", "azimuth_deg", json(12.0));
  doc.preview_sequence(40);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.get_field(sun, "core.DirectionalLight", "elevation_deg"), own);
  EXPECT_FALSE(doc.scene_dirty());
}

TEST_F(Timeline, PreviewReportsTracksItCannotApply) {
  Sequence s = with_key({}, "nobody", kElevation, 0, 1);
  s = with_key(s, "sun", kElevation, 0, 500);  // out of range
  doc.set_sequence(s, "keys");
  auto problems = doc.preview_sequence(0);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("nobody"), std::string::npos);
  EXPECT_NE(problems[1].find("range"), std::string::npos) << problems[1];
}

TEST_F(Timeline, LoadSequenceIsUndoable) {
  ScratchDir dir("timeline-load");
  Sequence s = with_key({}, "sun", kElevation, 0, 1);
  auto path = (dir.path() / "s.json").string();
  save_sequence_file(path, s);
  doc.load_sequence(path);
  EXPECT_EQ(doc.sequence(), s);
  doc.undo();
  EXPECT_TRUE(doc.sequence().tracks.empty());
}

}  // namespace
