#include "model/sequence.h"

#include <algorithm>
#include <cmath>

#include "welkin/core/error.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

// Names as files spell them, in the order of welkin::Interpolation and welkin::Easing.
constexpr const char* kInterpolationNames[] = {"step", "linear", "smooth", "cubic"};
constexpr const char* kEasingNames[] = {"none", "ease_in", "ease_out", "ease_in_out"};
static_assert(int(Interpolation::cubic) == 3 && int(Easing::ease_in_out) == 3);

// A key value's numbers (empty for names and booleans, which step).
std::vector<double> numbers_of(const json& v) {
  if (v.is_number()) return {v.get<double>()};
  std::vector<double> out;
  if (v.is_array())
    for (const json& c : v) out.push_back(c.get<double>());
  return out;
}

SequenceTrack& track_for(Sequence& s, const std::string& entity, const std::string& target, const json& value) {
  for (auto& t : s.tracks)
    if (t.entity == entity && t.target == target) return t;
  bool numeric = value.is_number() || value.is_array();
  s.tracks.push_back(SequenceTrack{.target = target, .entity = entity,
                                   .interpolation = numeric ? Interpolation::linear : Interpolation::step});
  return s.tracks.back();
}

}  // namespace

const char* interpolation_name(Interpolation i) { return kInterpolationNames[int(i)]; }
const char* easing_name(Easing e) { return kEasingNames[int(e)]; }

TrackTarget split_track_target(const std::string& target) {
  auto slash = target.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == target.size())
    throw Error(ErrorInfo{.expected = "component/field/path, e.g. core.DirectionalLight/elevation_deg", .found = "'" + target + "'"});
  return {target.substr(0, slash), target.substr(slash + 1)};
}

namespace {

// Builds the document in the order a reader expects (version, description, duration, tracks);
// with nlohmann::ordered_json that order reaches the file.
template <class J> J sequence_document(const Sequence& s) {
  J tracks = J::array();
  for (const auto& t : s.tracks) {
    J keys = J::array();
    for (const auto& k : t.keys) {
      J jk = J::object();
      jk["t"] = k.t;
      jk["value"] = J::parse(k.value.dump());
      if (k.easing != Easing::none) jk["easing"] = easing_name(k.easing);
      keys.push_back(std::move(jk));
    }
    J jt = J::object();
    jt["target"] = t.target;
    if (!t.entity.empty()) jt["entity"] = t.entity;
    jt["interpolation"] = interpolation_name(t.interpolation);
    if (t.wrap > 0) jt["wrap"] = t.wrap;
    if (t.optional) jt["optional"] = true;
    jt["keys"] = std::move(keys);
    tracks.push_back(std::move(jt));
  }
  J doc = J::object();
  doc["welkin_sequence"] = kSequenceFormatVersion;
  if (!s.description.empty()) doc["description"] = s.description;
  doc["duration_s"] = s.duration_s;
  doc["tracks"] = std::move(tracks);
  return doc;
}

}  // namespace

json sequence_to_json(const Sequence& s) { return sequence_document<json>(s); }

Sequence sequence_from_json(const json& doc, const std::string& file) {
  const welkin::Sequence parsed = parse_sequence(doc, file);  // validates, with the file and JSON path
  Sequence s;
  if (auto d = doc.find("description"); d != doc.end()) {
    if (!d->is_string()) throw Error(ErrorInfo{.file = file, .path = "/description", .expected = "string", .found = describe_json(*d)});
    s.description = d->get<std::string>();
  }
  if (parsed.duration_s > 0) s.duration_s = parsed.duration_s;  // else (no keys after 0, no duration) the default
  for (const welkin::Track& t : parsed.tracks) {
    SequenceTrack& track = s.tracks.emplace_back(SequenceTrack{.target = t.component + "/" + t.field, .entity = t.entity,
                                                               .interpolation = t.interpolation, .wrap = t.wrap,
                                                               .optional = t.optional});
    for (const welkin::Keyframe& k : t.keys) track.keys.push_back(Keyframe{.t = k.t, .value = k.raw, .easing = k.easing});
  }
  return s;
}

Sequence load_sequence_file(const std::string& path) { return sequence_from_json(read_json_file(path), path); }

void save_sequence_file(const std::string& path, const Sequence& s) {
  write_file_atomically(path, sequence_document<nlohmann::ordered_json>(s).dump(2) + "\n");
}

welkin::Track to_runtime_track(const SequenceTrack& track) {
  TrackTarget target = split_track_target(track.target);
  welkin::Track t{.component = target.component, .field = target.path, .entity = track.entity,
                  .interpolation = track.interpolation, .wrap = track.wrap, .optional = track.optional};
  for (const Keyframe& k : track.keys)
    t.keys.push_back(welkin::Keyframe{.t = k.t, .value = numbers_of(k.value), .raw = k.value, .easing = k.easing});
  return t;
}

json evaluate_track_value(const SequenceTrack& track, double t) {
  const auto& k = track.keys;
  if (k.empty()) return nullptr;
  bool numeric = k.front().value.is_number() || k.front().value.is_array();
  if (!numeric || track.interpolation == Interpolation::step) {  // the key at or before t (names and booleans always step)
    const Keyframe* key = &k.front();
    for (const Keyframe& x : k)
      if (x.t <= t) key = &x;
    return key->value;
  }
  std::vector<double> v = evaluate_track(to_runtime_track(track), t);
  return k.front().value.is_number() ? json(v.at(0)) : json(v);
}

Sequence with_key(Sequence s, const std::string& entity, const std::string& target, double t, const json& value) {
  split_track_target(target);
  if (!std::isfinite(t) || t < 0) throw Error(ErrorInfo{.path = target, .expected = "a key time >= 0", .found = std::to_string(t)});
  bool numeric = value.is_number() || value.is_array();
  if (!numeric && !value.is_string() && !value.is_boolean())
    throw Error(ErrorInfo{.path = target, .expected = "a number, vector, name or boolean to key", .found = describe_json(value)});
  SequenceTrack& track = track_for(s, entity, target, value);
  if (!numeric && track.interpolation != Interpolation::step) track.interpolation = Interpolation::step;
  auto it = std::find_if(track.keys.begin(), track.keys.end(), [&](const Keyframe& k) { return k.t > t - kKeyTimeEpsilon; });
  if (it != track.keys.end() && std::abs(it->t - t) < kKeyTimeEpsilon) it->value = value;
  else track.keys.insert(it, Keyframe{.t = t, .value = value});
  s.duration_s = std::max(s.duration_s, t);
  return s;
}

Sequence without_key(Sequence s, const std::string& entity, const std::string& target, double t) {
  for (size_t i = 0; i < s.tracks.size(); ++i) {
    SequenceTrack& track = s.tracks[i];
    if (track.entity != entity || track.target != target) continue;
    std::erase_if(track.keys, [&](const Keyframe& k) { return std::abs(k.t - t) < kKeyTimeEpsilon; });
    if (track.keys.empty()) s.tracks.erase(s.tracks.begin() + long(i));
    break;
  }
  return s;
}

Sequence with_key_moved(Sequence s, const std::string& entity, const std::string& target, double from_t, double to_t) {
  const SequenceTrack* track = find_track(s, entity, target);
  if (!track) return s;
  for (const Keyframe& k : track->keys)
    if (std::abs(k.t - from_t) < kKeyTimeEpsilon) {
      Keyframe moved = k;
      moved.t = to_t;
      // Remove and re-insert, keeping the key's easing; the track survives even when it held one key.
      SequenceTrack& mutable_track = *std::find_if(s.tracks.begin(), s.tracks.end(),
                                                   [&](const SequenceTrack& x) { return x.entity == entity && x.target == target; });
      std::erase_if(mutable_track.keys, [&](const Keyframe& x) { return std::abs(x.t - from_t) < kKeyTimeEpsilon; });
      std::erase_if(mutable_track.keys, [&](const Keyframe& x) { return std::abs(x.t - to_t) < kKeyTimeEpsilon; });
      auto at = std::find_if(mutable_track.keys.begin(), mutable_track.keys.end(), [&](const Keyframe& x) { return x.t > to_t; });
      mutable_track.keys.insert(at, moved);
      s.duration_s = std::max(s.duration_s, to_t);
      return s;
    }
  return s;
}

const SequenceTrack* find_track(const Sequence& s, const std::string& entity, const std::string& target) {
  for (const auto& t : s.tracks)
    if (t.entity == entity && t.target == target) return &t;
  return nullptr;
}

}  // namespace welkin::editor
