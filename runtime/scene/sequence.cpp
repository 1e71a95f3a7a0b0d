#include "welkin/scene/sequence.h"

#include <algorithm>
#include <cmath>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin {

using nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& expected,
                       const json& found, const std::string& message = {}) {
  throw Error(ErrorInfo{
      .file = file, .path = path, .expected = expected, .found = describe_json(found), .message = message});
}

double finite_number(const json& j, const std::string& file, const std::string& path) {
  if (!j.is_number()) fail(file, path, "number", j);
  double v = j.get<double>();
  if (!std::isfinite(v)) fail(file, path, "finite number", j);
  return v;
}

template <class E>
E parse_enum(const json& j, const std::vector<std::pair<const char*, E>>& names, const std::string& file,
             const std::string& path) {
  std::string all;
  for (const auto& [n, v] : names) all += (all.empty() ? "" : ", ") + std::string("\"") + n + "\"";
  if (j.is_string())
    for (const auto& [n, v] : names)
      if (j.get<std::string>() == n) return v;
  fail(file, path, "one of " + all, j);
}

void check_keys(const json& obj, std::initializer_list<const char*> allowed, const std::string& file,
                const std::string& path) {
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (std::find_if(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; }) ==
        allowed.end()) {
      std::string names;
      for (const char* a : allowed) names += (names.empty() ? "" : ", ") + std::string("\"") + a + "\"";
      fail(file, path + "/" + it.key(), "one of " + names, json(it.key()), "unknown key");
    }
}

double ease(Easing e, double u) {
  switch (e) {
    case Easing::none: return u;
    case Easing::ease_in: return u * u;
    case Easing::ease_out: return 1.0 - (1.0 - u) * (1.0 - u);
    case Easing::ease_in_out: return u < 0.5 ? 2.0 * u * u : 1.0 - 2.0 * (1.0 - u) * (1.0 - u);
  }
  return u;
}

// Shortest signed difference on a circle of the given period.
double wrapped_delta(double d, double period) {
  d = std::fmod(d, period);
  if (d > period / 2) d -= period;
  if (d < -period / 2) d += period;
  return d;
}

}  // namespace

Sequence parse_sequence(const json& doc, const std::string& file) {
  if (!doc.is_object()) fail(file, "/", "a sequence object", doc);
  check_keys(doc, {"welkin_sequence", "duration_s", "tracks", "description"}, file, "");
  auto ver = doc.find("welkin_sequence");
  if (ver == doc.end() || !ver->is_number_integer() || ver->get<int>() != 1)
    fail(file, "/welkin_sequence", "sequence format version 1", ver == doc.end() ? json("nothing") : *ver);
  Sequence seq;
  seq.file = file;
  auto tracks = doc.find("tracks");
  if (tracks == doc.end() || !tracks->is_array())
    fail(file, "/tracks", "array of tracks", tracks == doc.end() ? json() : *tracks);
  double last_key = 0;
  for (size_t i = 0; i < tracks->size(); ++i) {
    std::string tp = "/tracks/" + std::to_string(i);
    const json& tj = (*tracks)[i];
    if (!tj.is_object()) fail(file, tp, "track object", tj);
    check_keys(tj, {"target", "entity", "interpolation", "wrap", "optional", "keys"}, file, tp);
    Track tr;
    tr.json_path = tp;
    auto target = tj.find("target");
    if (target == tj.end() || !target->is_string())
      fail(file, tp + "/target", "\"component/field/path\"", target == tj.end() ? json() : *target);
    std::string t = target->get<std::string>();
    auto slash = t.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == t.size())
      fail(file, tp + "/target", "\"component/field/path\", e.g. \"core.Camera/vertical_fov_deg\"", *target);
    tr.component = t.substr(0, slash);
    tr.field = t.substr(slash + 1);
    if (auto e = tj.find("entity"); e != tj.end()) {
      if (!e->is_string()) fail(file, tp + "/entity", "entity name", *e);
      tr.entity = e->get<std::string>();
    }
    if (auto in = tj.find("interpolation"); in != tj.end())
      tr.interpolation = parse_enum<Interpolation>(*in,
                                                   {{"step", Interpolation::step},
                                                    {"linear", Interpolation::linear},
                                                    {"smooth", Interpolation::smooth},
                                                    {"cubic", Interpolation::cubic}},
                                                   file, tp + "/interpolation");
    if (auto w = tj.find("wrap"); w != tj.end()) {
      tr.wrap = finite_number(*w, file, tp + "/wrap");
      if (tr.wrap <= 0) fail(file, tp + "/wrap", "a positive period (360 for degrees, 24 for hours)", *w);
    }
    if (auto o = tj.find("optional"); o != tj.end()) {
      if (!o->is_boolean()) fail(file, tp + "/optional", "true or false", *o);
      tr.optional = o->get<bool>();
    }
    auto keys = tj.find("keys");
    if (keys == tj.end() || !keys->is_array())
      fail(file, tp + "/keys", "array of keyframes", keys == tj.end() ? json() : *keys);
    if (keys->empty()) fail(file, tp + "/keys", "at least one keyframe", *keys, "empty track");
    bool numeric = true;
    for (size_t k = 0; k < keys->size(); ++k) {
      std::string kp = tp + "/keys/" + std::to_string(k);
      const json& kj = (*keys)[k];
      if (!kj.is_object()) fail(file, kp, "keyframe object {\"t\", \"value\"}", kj);
      check_keys(kj, {"t", "value", "easing"}, file, kp);
      Keyframe key;
      if (!kj.contains("t")) fail(file, kp + "/t", "time in seconds", json("nothing"));
      key.t = finite_number(kj["t"], file, kp + "/t");
      if (key.t < 0) fail(file, kp + "/t", "time >= 0", kj["t"]);
      if (!tr.keys.empty() && key.t <= tr.keys.back().t)
        fail(file, kp + "/t", "a time after " + std::to_string(tr.keys.back().t) + " s", kj["t"],
             "keyframes out of order");
      if (!kj.contains("value")) fail(file, kp + "/value", "a value", json("nothing"));
      key.raw = kj["value"];
      if (key.raw.is_number()) {
        key.value = {finite_number(key.raw, file, kp + "/value")};
      } else if (key.raw.is_array()) {
        for (size_t c = 0; c < key.raw.size(); ++c)
          key.value.push_back(finite_number(key.raw[c], file, kp + "/value/" + std::to_string(c)));
        if (key.value.empty()) fail(file, kp + "/value", "a non-empty array", key.raw);
      } else if (key.raw.is_string() || key.raw.is_boolean()) {
        numeric = false;
      } else {
        fail(file, kp + "/value", "number, array of numbers, boolean or enumeration name", key.raw);
      }
      if (!tr.keys.empty() && numeric && key.value.size() != tr.keys.back().value.size())
        fail(file, kp + "/value",
             std::to_string(tr.keys.back().value.size()) + " components like the previous key", key.raw);
      if (auto e = kj.find("easing"); e != kj.end())
        key.easing = parse_enum<Easing>(*e,
                                        {{"none", Easing::none},
                                         {"ease_in", Easing::ease_in},
                                         {"ease_out", Easing::ease_out},
                                         {"ease_in_out", Easing::ease_in_out}},
                                        file, kp + "/easing");
      tr.keys.push_back(std::move(key));
    }
    if (!numeric && tr.interpolation != Interpolation::step)
      fail(file, tp + "/interpolation", "\"step\" for non-numeric values",
           tj.value("interpolation", json("linear")));
    last_key = std::max(last_key, tr.keys.back().t);
    seq.tracks.push_back(std::move(tr));
  }
  seq.duration_s = last_key;
  if (auto d = doc.find("duration_s"); d != doc.end()) {
    seq.duration_s = finite_number(*d, file, "/duration_s");
    if (seq.duration_s <= 0) fail(file, "/duration_s", "a positive duration", *d);
  }
  return seq;
}

Sequence load_sequence_file(const std::string& path) { return parse_sequence(read_json_file(path), path); }

std::vector<double> evaluate_track(const Track& tr, double t) {
  const auto& k = tr.keys;
  if (t <= k.front().t || k.size() == 1) return k.front().value;
  if (t >= k.back().t) return k.back().value;
  size_t i = size_t(std::upper_bound(k.begin(), k.end(), t,
                                     [](double x, const Keyframe& key) { return x < key.t; }) -
                    k.begin()) -
             1;
  const Keyframe& a = k[i];
  const Keyframe& b = k[i + 1];
  if (tr.interpolation == Interpolation::step) return a.value;
  double u = ease(b.easing, (t - a.t) / (b.t - a.t));
  if (tr.interpolation == Interpolation::smooth) u = u * u * (3.0 - 2.0 * u);
  // Work on an unwrapped copy of the neighbouring values so a wrap crosses 360 or midnight the short way.
  auto value_at = [&](size_t idx, size_t c, double reference) {
    double v = k[idx].value[c];
    return tr.wrap > 0 ? reference + wrapped_delta(v - reference, tr.wrap) : v;
  };
  std::vector<double> out(a.value.size());
  for (size_t c = 0; c < out.size(); ++c) {
    double p0 = a.value[c];
    double p1 = value_at(i + 1, c, p0);
    double v;
    if (tr.interpolation == Interpolation::cubic) {
      // Cubic Hermite with Catmull-Rom tangents for uneven key spacing (one-sided at the ends).
      double dt = b.t - a.t;
      double m0 = i > 0 ? (p1 - value_at(i - 1, c, p0)) / (b.t - k[i - 1].t) : (p1 - p0) / dt;
      double m1 = i + 2 < k.size() ? (value_at(i + 2, c, p1) - p0) / (k[i + 2].t - a.t) : (p1 - p0) / dt;
      double u2 = u * u, u3 = u2 * u;
      v = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * dt * m0 + (-2 * u3 + 3 * u2) * p1 +
          (u3 - u2) * dt * m1;
    } else {
      v = p0 + (p1 - p0) * u;
    }
    if (tr.wrap > 0) v -= tr.wrap * std::floor(v / tr.wrap);
    out[c] = v;
  }
  return out;
}

void apply_sequence(const Sequence& seq, World& world, double t) {
  Registry& reg = world.registry();
  for (const Track& tr : seq.tracks) {
    auto located = [&](const Error& e) {
      return Error(ErrorInfo{.file = seq.file, .path = tr.json_path + "/target", .message = e.what()});
    };
    const ComponentInfo* info = nullptr;
    try {
      info = &world.modules().require_component(tr.component);
    } catch (const Error& e) {
      if (tr.optional) continue;
      throw located(e);
    }
    Entity target;
    if (const ComponentPool* pool = reg.pool(info->type->id))
      for (Entity e : pool->entities()) {
        const Name* n = reg.get<Name>(e);
        if (tr.entity.empty() || (n && n->value == tr.entity)) {
          target = e;
          break;
        }
      }
    if (target.is_null()) {
      if (tr.optional) continue;
      throw Error(ErrorInfo{.file = seq.file, .path = tr.json_path + "/target",
                            .message = "no entity" + (tr.entity.empty() ? "" : " named '" + tr.entity + "'") +
                                       " has component " + tr.component});
    }
    try {
      FieldRef ref = resolve_field(*info->type, reg.get(target, info->type->id), tr.field);
      const Keyframe& first = tr.keys.front();
      if (first.value.empty()) {  // non-numeric: step between the values as written
        const Keyframe* key = &first;
        for (const Keyframe& k : tr.keys)
          if (k.t <= t) key = &k;
        ref.set_json(key->raw);
        continue;
      }
      std::vector<double> v = evaluate_track(tr, t);
      FieldKind kind = ref.field->kind;
      if (v.size() == 1) {
        bool integral =
            kind == FieldKind::integer || kind == FieldKind::enumeration || kind == FieldKind::boolean;
        ref.set_scalar(integral && ref.component < 0 ? std::round(v[0]) : v[0]);
      } else {
        ref.set_json(json(v));
      }
    } catch (const Error& e) {
      throw Error(ErrorInfo{.file = seq.file, .path = tr.json_path, .message = e.what()});
    }
  }
}

}  // namespace welkin
