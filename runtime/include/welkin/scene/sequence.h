#pragma once
// Keyframed sequences (time-of-day scripts, camera flights, preset blends): tracks that target any reflected
// field by path
// ("timeofday.TimeOfDay/local_time_h", "core.Camera/position_m",
// "clouds.VolumetricClouds/layers/0/coverage"), with step, linear, smooth or cubic Hermite interpolation,
// per-key easing and wrapping for angles and clock times. Evaluation is a pure function of time, so scrubbing
// equals playing.
//
// { "welkin_sequence": 1, "duration_s": 20,
//   "tracks": [ { "target": "timeofday.TimeOfDay/local_time_h", "interpolation": "smooth", "wrap": 24,
//                 "keys": [ { "t": 0, "value": 23.5 }, { "t": 10, "value": 0.5, "easing": "ease_in_out" } ] }
//                 ] }
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace welkin {

class World;

enum class Interpolation { step, linear, smooth, cubic };
enum class Easing { none, ease_in, ease_out, ease_in_out };

struct Keyframe {
  double t = 0;
  std::vector<double> value;  // one number, or a vector's components
  nlohmann::json raw;         // the value as written (non-numeric values, e.g. enum names, use step)
  Easing easing = Easing::none;  // shapes the segment that ends at this key
};

struct Track {
  std::string component;  // "timeofday.TimeOfDay"
  std::string field;      // "local_time_h", "layers/0/coverage"
  std::string entity;     // optional entity name; empty: the first entity with the component
  Interpolation interpolation = Interpolation::linear;
  double wrap = 0;        // period for angles (360) and clock times (24); 0: no wrapping
  bool optional = false;  // a missing component or module is skipped instead of an error
  std::vector<Keyframe> keys;
  std::string json_path;  // "/tracks/3", for messages
};

struct Sequence {
  std::string file;
  double duration_s = 0;
  std::vector<Track> tracks;
};

// Parses and validates a sequence document; throws Error with the file and JSON path.
Sequence parse_sequence(const nlohmann::json& doc, const std::string& file);
Sequence load_sequence_file(const std::string& path);

// The track's value at time t (clamped to its first and last keys).
std::vector<double> evaluate_track(const Track& track, double t);

// Writes every track's value at time t into the world; throws Error for a non-optional track whose
// target does not exist (file and track path in the message).
void apply_sequence(const Sequence& sequence, World& world, double t);

}  // namespace welkin
