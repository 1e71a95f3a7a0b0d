#pragma once
// The timeline's document: a sequence file (welkin/scene/sequence.h) in an editable form. Parsing,
// evaluation and applying are the runtime's (welkin::parse_sequence, evaluate_track,
// apply_sequence); this adds what editing needs: values kept as written, the description, key
// edits, equality for undo, and writing the file back in the same format.
//
// { "welkin_sequence": 1, "duration_s": 20, "description": "...",
//   "tracks": [ { "target": "timeofday.TimeOfDay/local_time_h", "interpolation": "smooth", "wrap": 24,
//                 "keys": [ { "t": 0, "value": 23.5 }, { "t": 10, "value": 0.5, "easing": "ease_in_out" } ] } ] }
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "welkin/scene/sequence.h"

namespace welkin::editor {

inline constexpr int kSequenceFormatVersion = 1;

// welkin::Interpolation and welkin::Easing, as written in files.
const char* interpolation_name(Interpolation i);
const char* easing_name(Easing e);

struct Keyframe {
  double t = 0;
  nlohmann::json value;          // a number, an array of numbers, or (step tracks) a name or boolean
  Easing easing = Easing::none;  // shapes the segment that ends at this key
  friend bool operator==(const Keyframe&, const Keyframe&) = default;
};

struct SequenceTrack {
  std::string target;  // "component/field/path"
  std::string entity;  // entity name; empty: the first entity with the component
  Interpolation interpolation = Interpolation::linear;
  double wrap = 0;        // period for angles (360) and clock times (24); 0: none
  bool optional = false;  // a missing component or module is skipped, not an error
  std::vector<Keyframe> keys;  // sorted by time, at least one in a file
  friend bool operator==(const SequenceTrack&, const SequenceTrack&) = default;
};

struct Sequence {
  double duration_s = 60;
  std::string description;
  std::vector<SequenceTrack> tracks;
  friend bool operator==(const Sequence&, const Sequence&) = default;
};

// A track target split at its first slash: component name and field path.
struct TrackTarget {
  std::string component, path;
};
// Throws Error when `target` is not "component/path".
TrackTarget split_track_target(const std::string& target);

// The file format welkin::parse_sequence reads (the runtime has no writer yet).
nlohmann::json sequence_to_json(const Sequence& sequence);
// Validated by welkin::parse_sequence; throws Error with the file and JSON path.
Sequence sequence_from_json(const nlohmann::json& doc, const std::string& file);
Sequence load_sequence_file(const std::string& path);
// Atomic (temporary file, then rename).
void save_sequence_file(const std::string& path, const Sequence& sequence);

// The runtime's form of a track (for welkin::evaluate_track and welkin::apply_sequence).
welkin::Track to_runtime_track(const SequenceTrack& track);
// The track's value at time t, clamped to its first and last keys: welkin::evaluate_track for
// numbers, the key at or before t for names and booleans (as welkin::apply_sequence steps them).
nlohmann::json evaluate_track_value(const SequenceTrack& track, double t);

// Pure edits, returning the changed copy (the document records before/after for undo).
// Adds a key, replacing one at the same time; a new track steps when the value is not numeric.
Sequence with_key(Sequence s, const std::string& entity, const std::string& target, double t, const nlohmann::json& value);
// Removes the key at `t` (and the track when it becomes empty); unchanged when there is none.
Sequence without_key(Sequence s, const std::string& entity, const std::string& target, double t);
// Moves one key in time (replacing a key already at the new time).
Sequence with_key_moved(Sequence s, const std::string& entity, const std::string& target, double from_t, double to_t);

const SequenceTrack* find_track(const Sequence& s, const std::string& entity, const std::string& target);
// Times closer than this are the same key.
inline constexpr double kKeyTimeEpsilon = 1e-6;

}  // namespace welkin::editor
