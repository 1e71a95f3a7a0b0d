#include "session_fuzz.h"

#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "model/preset_library.h"
#include "model/script.h"
#include "model/sequence.h"
#include "model/session_guard.h"
#include "test_module.h"
#include "welkin/core/error.h"
#include "welkin/scene/painted_map.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor::fuzz {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kSecondsPerLine = 7.0;  // the autosave's clock: one line is a few seconds of editing
constexpr size_t kMaxUndoSteps = 4000;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return in ? std::string(std::istreambuf_iterator<char>(in), {}) : std::string("<missing>");
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// What the editor's promises are about: the scene, its painted maps and the sequence, as bytes.
struct State {
  std::string scene, maps, sequence;
  bool scene_dirty = false, sequence_dirty = false;
};

// Where two texts first differ, for a readable failure.
std::string first_difference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  size_t from = i > 60 ? i - 60 : 0;
  return "at byte " + std::to_string(i) + ": '" + a.substr(from, 120) + "' vs '" + b.substr(from, 120) + "'";
}

std::string compare(const State& want, const State& got, bool flags) {
  if (want.scene != got.scene) return "scene differs " + first_difference(want.scene, got.scene);
  if (want.maps != got.maps) return "painted maps differ " + first_difference(want.maps, got.maps);
  if (want.sequence != got.sequence)
    return "sequence differs " + first_difference(want.sequence, got.sequence);
  if (flags && (want.scene_dirty != got.scene_dirty || want.sequence_dirty != got.sequence_dirty))
    return "dirty flags differ (scene " + std::to_string(want.scene_dirty) + " -> " +
           std::to_string(got.scene_dirty) + ", sequence " + std::to_string(want.sequence_dirty) + " -> " +
           std::to_string(got.sequence_dirty) + ")";
  return {};
}

// A scene file as the editor's own writer spells it (loaded into a fresh world, saved again).
std::string normalized_scene_file(const std::string& path) {
  try {
    auto world = editor_test::make_test_world();
    load_scene_file(*world, path);
    return save_scene(*world).dump();
  } catch (const Error& e) {
    return std::string("<unreadable: ") + e.what() + ">";
  }
}

std::string normalized_sequence_file(const std::string& path) {
  try {
    return sequence_to_json(load_sequence_file(path)).dump();
  } catch (const Error& e) {
    return std::string("<unreadable: ") + e.what() + ">";
  }
}

// The map files the scene's test.Weather components name.
std::vector<std::string> map_files(EditorDocument& doc) {
  std::vector<std::string> files;
  for (const EntityRow& row : doc.entities()) {
    json w = doc.get_component(row.id, "test.Weather");
    if (w.is_object() && w["map"].is_string() && !w["map"].get<std::string>().empty())
      files.push_back(w["map"].get<std::string>());
  }
  return files;
}

std::string map_text(const PaintedMap& m) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a of the texels
  for (uint8_t t : m.texels) h = (h ^ t) * 1099511628211ull;
  return std::to_string(m.side) + ":" + std::to_string(h);
}

State state_of(EditorDocument& doc) {
  doc.end_preview();  // the document as it would be saved: a preview is not part of it
  State s;
  s.scene = save_scene(doc.world()).dump();
  for (const std::string& file : map_files(doc)) {
    s.maps += file + "=";
    try {
      s.maps += map_text(doc.world().resource<PaintedMaps>().get(file));
    } catch (const Error&) {
      s.maps += "<unreadable>";
    }
    s.maps += "\n";
  }
  s.sequence = sequence_to_json(doc.sequence()).dump();
  s.scene_dirty = doc.scene_dirty();
  s.sequence_dirty = doc.sequence_dirty();
  return s;
}

// The autosave's files, as bytes: a write shows as a change.
std::string autosave_bytes(const fs::path& folder) {
  return read_text(folder / "meta.json") + "|" + read_text(folder / "scene.json") + "|" +
         read_text(folder / "sequence.json");
}

// Every file of the session's folder outside the autosave (what the user saved).
std::map<std::string, std::string> saved_files(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().parent_path().filename() != "autosave")
      files[e.path().string()] = read_text(e.path());
  return files;
}

// One editor session: the document, presets and session guard an editor holds, and what the checks
// remember between lines.
class Session {
 public:
  explicit Session(const FuzzFolder& folder) : folder_(folder) {
    start();
    doc_->load_scene((folder_.root() / "scene.json").string());
    base_ = state_of(*doc_);
    generation_ = doc_->world_generation();
  }

  EditorDocument& doc() { return *doc_; }
  SessionGuard& guard() { return *guard_; }

  // Runs one script line and checks every invariant; the broken one, or empty.
  std::string step(const std::string& text) {
    std::vector<ScriptLine> lines = parse_script(text, "fuzz");
    if (lines.empty()) return {};
    const ScriptLine& line = lines.front();
    if (line.verb == "crash") return crash();
    const State before = state_of(*doc_);
    const std::optional<Prompt> prompt = guard_->prompt();
    const auto files_before = saved_files(folder_.root());
    const std::optional<AutosaveContents> autosaved = guard_->autosave().find();
    bool ok = true;
    try {
      if (prompt && !verb_allowed_during_prompt(line.verb)) throw Error("a prompt waits");
      std::string output;
      if (!run_session_verb(*guard_, *doc_, line) && !run_document_verb(*doc_, *presets_, line, output))
        throw Error("unknown verb " + line.verb);
    } catch (const Error&) {
      ok = false;
    }
    const State after = state_of(*doc_);
    // A failed line changes nothing; but an answer "save" that saved and then could not go on (the
    // file to open does not load) has rightly left the saved parts clean.
    if (!ok)
      if (std::string d = compare(before, after, line.verb != "answer"); !d.empty())
        return "failed-line-changed-state: " + d;
    if (std::string f = check_recovery(line, prompt, autosaved, files_before, after); !f.empty()) return f;
    if (ok && line.verb == "save-scene" && !guard_->prompt() && doc_->scene_dirty())
      return "save-left-dirty: the scene";
    if (ok && line.verb == "save-sequence" && doc_->sequence_dirty()) return "save-left-dirty: the sequence";
    if (std::string f = tick(); !f.empty()) return f;
    if (doc_->world_generation() != generation_) {  // loaded, new or recovered: a new history began
      generation_ = doc_->world_generation();
      base_ = undone_state();
    }
    if (std::string f = check_undo_redo(); !f.empty()) return f;
    return check_clean_parts();
  }

 private:
  void start() {
    doc_ = std::make_unique<EditorDocument>(editor_test::make_test_world);
    presets_ = std::make_unique<PresetLibrary>(editor_test::make_test_world());
    presets_->rescan();
    guard_ = std::make_unique<SessionGuard>(*doc_, Autosave(folder_.root() / "autosave"));
  }

  // As `crash` leaves the editor: no prompt answered, the autosave in place. The next start opens
  // the last scene (the command line's, say) and offers the autosave back.
  std::string crash() {
    const std::string scene = doc_->scene_path();
    const std::string autosave_before = autosave_bytes(folder_.root() / "autosave");
    guard_.reset();
    presets_.reset();
    doc_.reset();
    start();
    try {
      if (!scene.empty()) doc_->load_scene(scene);
    } catch (const Error&) {
      doc_->new_scene();
    }
    guard_->offer_recovery();
    generation_ = doc_->world_generation();
    base_ = state_of(*doc_);
    if (autosave_bytes(folder_.root() / "autosave") != autosave_before) return "restart-wrote-autosave";
    return check_clean_parts();
  }

  // After `answer recover`: each recovered part is what the autosave holds, dirty, under its original
  // file name, and no file the user saved changed.
  std::string check_recovery(const ScriptLine& line, const std::optional<Prompt>& prompt,
                             const std::optional<AutosaveContents>& autosaved,
                             const std::map<std::string, std::string>& files_before, const State& after) {
    if (!prompt || prompt->kind != PromptKind::recover || line.verb != "answer" || guard_->prompt())
      return {};
    if (line.args.size() != 1 || line.args[0] != "recover") return {};
    if (!autosaved) return "recover-without-autosave";
    const fs::path folder = folder_.root() / "autosave";
    if (autosaved->scene) {
      if (after.scene != normalized_scene_file((folder / "scene.json").string()))
        return "recovered-scene: " +
               first_difference(after.scene, normalized_scene_file((folder / "scene.json").string()));
      if (!doc_->scene_dirty() || doc_->scene_path() != autosaved->scene_path)
        return "recovered-scene-not-dirty-or-renamed";
    }
    if (autosaved->sequence) {
      if (after.sequence != normalized_sequence_file((folder / "sequence.json").string()))
        return "recovered-sequence";
      if (!doc_->sequence_dirty() || doc_->sequence_path() != autosaved->sequence_path)
        return "recovered-sequence-not-dirty-or-renamed";
    }
    if (saved_files(folder_.root()) != files_before) return "recover-changed-a-saved-file";
    return {};
  }

  // The autosave clock moves on; whatever the guard writes must be the document as it is now, and
  // nothing may overwrite the last session's autosave while its recover prompt waits.
  std::string tick() {
    const fs::path folder = folder_.root() / "autosave";
    const std::string before = autosave_bytes(folder);
    clock_s_ += kSecondsPerLine;
    guard_->tick(clock_s_);
    const std::string now = autosave_bytes(folder);
    if (guard_->prompt() && guard_->prompt()->kind == PromptKind::recover) {
      return now == before ? std::string() : "autosave-overwritten-before-recovery";
    }
    if (now == last_autosave_) return {};
    last_autosave_ = now;
    const std::optional<AutosaveContents> contents = guard_->autosave().find();
    if (!contents) return {};
    const State s = state_of(*doc_);
    if (contents->scene && normalized_scene_file((folder / "scene.json").string()) != s.scene)
      return "autosave-scene-is-not-the-document";
    if (contents->sequence && normalized_sequence_file((folder / "sequence.json").string()) != s.sequence)
      return "autosave-sequence-is-not-the-document";
    if (contents->scene != s.scene_dirty || contents->sequence != s.sequence_dirty)
      return "autosave-parts-are-not-the-unsaved-ones";
    return {};
  }

  // Undoes everything (the state when the history began), then redoes everything (the state now).
  State undone_state() {
    size_t undone = 0;
    while (undone < kMaxUndoSteps && doc_->undo()) ++undone;
    State s = state_of(*doc_);
    for (size_t i = 0; i < undone; ++i) doc_->redo();
    return s;
  }

  std::string check_undo_redo() {
    const State now = state_of(*doc_);
    size_t undone = 0;
    try {
      while (undone < kMaxUndoSteps && doc_->undo()) ++undone;
    } catch (const Error& e) {
      return std::string("undo-threw: ") + e.what();
    }
    if (std::string d = compare(base_, state_of(*doc_), false); !d.empty()) return "undo-all: " + d;
    try {
      for (size_t i = 0; i < undone; ++i)
        if (!doc_->redo())
          return "redo-all: stopped after " + std::to_string(i) + " of " + std::to_string(undone);
    } catch (const Error& e) {
      return std::string("redo-threw: ") + e.what();
    }
    if (std::string d = compare(now, state_of(*doc_), true); !d.empty()) return "redo-all: " + d;
    return {};
  }

  // A part that is not dirty holds what its file holds (editor/README.md).
  std::string check_clean_parts() {
    const State s = state_of(*doc_);
    if (!s.scene_dirty && !doc_->scene_path().empty()) {
      if (normalized_scene_file(doc_->scene_path()) != s.scene)
        return "clean-scene-differs-from-its-file: " +
               first_difference(normalized_scene_file(doc_->scene_path()), s.scene);
      for (const std::string& file : map_files(*doc_)) {
        PaintedMaps on_disk;
        std::string want;
        try {
          want = map_text(on_disk.get(file));
        } catch (const Error&) {
          want = "<unreadable>";
        }
        std::string got;
        try {
          got = map_text(doc_->world().resource<PaintedMaps>().get(file));
        } catch (const Error&) {
          got = "<unreadable>";
        }
        if (want != got) return "clean-scene-map-differs-from-its-file: " + file;
      }
    }
    if (!s.sequence_dirty && !doc_->sequence_path().empty() &&
        normalized_sequence_file(doc_->sequence_path()) != s.sequence)
      return "clean-sequence-differs-from-its-file";
    return {};
  }

  const FuzzFolder& folder_;
  std::unique_ptr<EditorDocument> doc_;
  std::unique_ptr<PresetLibrary> presets_;
  std::unique_ptr<SessionGuard> guard_;
  State base_;               // when the current history began
  uint64_t generation_ = 0;  // the document's world generation then
  double clock_s_ = 0;
  std::string last_autosave_;  // the autosave's bytes when last checked
};

// --- Random lines ----------------------------------------------------------------------------

class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 1) {}
  uint64_t next() {  // splitmix64: the same sessions on every platform
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return size_t(next() % n); }
  double uniform(double a, double b) { return a + (b - a) * double(next() >> 11) / double(1ull << 53); }
  bool chance(double p) { return uniform(0, 1) < p; }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[below(v.size())];
  }

 private:
  uint64_t s_;
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string layers(Rng& r) {
  std::string s = "[";
  for (size_t i = 0, n = r.below(6); i < n; ++i)  // up to 5: one more than the field allows
    s += (i ? ", " : "") + ("{\"coverage\": " + number(r.uniform(-0.1, 1.1)) +
                            ", \"octaves\": " + std::to_string(r.below(10)) + "}");
  return s + "]";
}

// A value for one of the test module's fields: mostly valid, sometimes out of range or mistyped.
std::string set_line(Rng& r) {
  switch (r.below(13)) {
    case 0:
      return "set test.Clouds/density " + number(r.uniform(-10, 110));
    case 1:
      return "set test.Clouds/steps " +
             (r.chance(0.1) ? std::string("2.5") : std::to_string(int(r.below(300)) - 5));
    case 2:
      return "set test.Clouds/altitude_m " + number(r.uniform(-100, 21000));
    case 3:
      return "set test.Clouds/mode " + r.pick<std::string>({"fast", "precise", "slow"});
    case 4:
      return "set test.Clouds/tint [" + number(r.uniform(-0.2, 1.2)) + ", " + number(r.uniform(0, 1)) +
             (r.chance(0.9) ? ", 0.5]" : "]");
    case 5:
      return "set test.Clouds/shadows " + r.pick<std::string>({"true", "false", "1"});
    case 6:
      return "set test.Clouds/label " + r.pick<std::string>({"cumulus", "\"alto stratus\"", "x"});
    case 7:
      return "set test.Clouds/layers " + layers(r);
    case 8:
      return "set test.Clouds/layers/" + std::to_string(r.below(5)) + "/coverage " +
             number(r.uniform(-0.1, 1.1));
    case 9:
      return "set test.Fog/visibility_km " + number(r.uniform(-1, 1200));
    case 10:
      return "set test.Weather/map_size_m " + number(r.uniform(10, 50000));
    case 11:
      return "set test.Weather/map " +
             r.pick<std::string>({"\"\"", "\"${FUZZ}/scene.map.png\"", "\"${FUZZ}/missing.png\""});
    default:
      return "set test.Clouds/density \"thick\"";
  }
}

const std::vector<std::string> kNames = {"deck", "weather", "fog", "extra", "spare"};
const std::vector<std::string> kComponents = {"test.Clouds", "test.Fog", "test.Weather"};

std::string answer_line(Rng& r, const Prompt& p) {
  if (r.chance(0.08))
    return "answer " + r.pick<std::string>({"save", "discard", "cancel", "overwrite", "recover"});
  switch (p.kind) {
    case PromptKind::unsaved:
      return "answer " + r.pick<std::string>({"save", "discard", "cancel"});
    case PromptKind::overwrite:
      return "answer " + r.pick<std::string>({"overwrite", "cancel"});
    case PromptKind::recover:
      return "answer " + r.pick<std::string>({"recover", "recover", "discard"});
  }
  return "answer cancel";
}

// One line, chosen by weight among the verbs.
std::string random_line(Rng& r, Session& s) {
  if (const auto& p = s.guard().prompt(); p && r.chance(0.9)) return answer_line(r, *p);
  struct Choice {
    int weight;
    std::function<std::string()> line;
  };
  const std::string time = number(double(r.below(13)) * 5);
  const std::vector<Choice> choices = {
      {26, [&] { return set_line(r); }},
      {12, [&] { return std::string("undo"); }},
      {8, [&] { return std::string("redo"); }},
      {4, [&] { return "select " + r.pick(kNames); }},
      {3, [&] { return "add-entity " + r.pick(kNames); }},
      {3, [&] { return "remove-entity " + r.pick(kNames); }},
      {2, [&] { return "rename-entity " + r.pick(kNames); }},
      {4, [&] { return "add-component " + r.pick(kComponents); }},
      {3, [&] { return "remove-component " + r.pick(kComponents); }},
      {4,
       [&] {
         return "apply-preset test " + r.pick<std::string>({"thin", "thick", "haze", "nosuch"});
       }},
      {3, [&] { return "blend-presets test thin thick " + number(r.uniform(-0.1, 1.1)); }},
      {2,
       [&] {
         return "revert-preset test " + r.pick<std::string>({"thin", "haze"});
       }},
      {1, [&] { return std::string("save-preset test thick"); }},
      {1, [&] { return "save-preset-as test.Clouds \"${FUZZ}/presets/mine.json\""; }},
      {2,
       [&] {
         return "new-map test.Weather/map " + r.pick<std::string>({"16", "32", "0"});
       }},
      {6,
       [&] {
         return "paint test.Weather/map " + number(r.uniform(-12000, 12000)) + " " +
                number(r.uniform(-12000, 12000)) + " " + number(r.uniform(200, 6000)) + " " +
                number(r.uniform(0, 1)) + " " + r.pick<std::string>({"add", "clear", "reset"});
       }},
      {5, [&] { return "key test.Clouds/density " + time + " " + number(r.uniform(0, 100)); }},
      {2,
       [&] {
         return "key test.Clouds/mode " + time + " " + r.pick<std::string>({"fast", "precise"});
       }},
      {2, [&] { return "key test.Fog/visibility_km " + time + " " + number(r.uniform(0.1, 900)); }},
      {3, [&] { return "unkey test.Clouds/density " + time; }},
      {4, [&] { return "time " + number(r.uniform(-5, 70)); }},
      {4,
       [&] {
         return "save-scene \"${FUZZ}/" + r.pick<std::string>({"scene.json", "scene.json", "other.json"}) +
                "\"";
       }},
      {2,
       [&] {
         return "load-scene \"${FUZZ}/" + r.pick<std::string>({"scene.json", "other.json", "bad.json"}) +
                "\"";
       }},
      {1, [&] { return std::string("new-scene"); }},
      {2,
       [&] {
         return "save-sequence \"${FUZZ}/" + r.pick<std::string>({"sequence.json", "second.json"}) + "\"";
       }},
      {2,
       [&] {
         return "load-sequence \"${FUZZ}/" +
                r.pick<std::string>({"sequence.json", "second.json", "bad.json"}) + "\"";
       }},
      {3, [&] { return std::string("autosave-now"); }},
      {2, [&] { return std::string("crash"); }},
  };
  int total = 0;
  for (const Choice& c : choices) total += c.weight;
  int at = int(r.below(size_t(total)));
  for (const Choice& c : choices) {
    if (at < c.weight) return c.line();
    at -= c.weight;
  }
  return "undo";
}

// The invariant a failure names (its first word), so shrinking keeps the same failure.
std::string kind_of(const std::string& what) {
  return what.substr(0, what.find(':'));
}

}  // namespace

FuzzFolder::FuzzFolder(fs::path root) : root_(std::move(root)) {
  ::setenv("FUZZ", root_.string().c_str(), 1);  // scripts name the folder ${FUZZ}
  editor_test::test_module_data_dir() = root_.string();
}

void FuzzFolder::reset() const {
  fs::remove_all(root_);
  write_text(root_ / "scene.json", R"({"welkin_scene": 1, "entities": [
    {"name": "deck", "components": {"test.Clouds": {"density": 2, "layers": [{"coverage": 0.3}, {"coverage": 0.6}]}}},
    {"name": "weather", "components": {"test.Weather": {"map_size_m": 30000}}},
    {"name": "fog", "components": {"test.Fog": {"visibility_km": 25}}}]})");
  write_text(root_ / "sequence.json", R"({"welkin_sequence": 1, "duration_s": 30, "tracks": [
    {"target": "test.Clouds/density", "entity": "deck", "keys": [{"t": 0, "value": 1}, {"t": 20, "value": 9}]}]})");
  write_text(root_ / "bad.json", "{\"welkin_scene\": 1, \"entities\": [");
  write_text(root_ / "presets/thin.json",
             R"({"density": 0.5, "steps": 8, "mode": "fast", "layers": [{"coverage": 0.1, "octaves": 2}]})");
  write_text(root_ / "presets/thick.json",
             R"({"density": 8, "steps": 64, "mode": "precise", "tint": [1, 0.5, 0],
                                              "layers": [{"coverage": 1, "octaves": 6}, {"coverage": 0.75, "octaves": 7}]})");
  write_text(root_ / "presets/haze.json", R"({"visibility_km": 2.5})");
  write_text(
      root_ / "editor/panels.json",
      R"({"panels": [{"title": "Weather map", "map": {"component": "test.Weather", "file_field": "map", "size_field": "map_size_m"}}]})");
}

std::optional<Failure> run_session(const FuzzFolder& folder, const std::vector<std::string>& lines) {
  folder.reset();
  Session session(folder);
  for (size_t i = 0; i < lines.size(); ++i)
    if (std::string f = session.step(lines[i]); !f.empty()) return Failure{i, f};
  return std::nullopt;
}

std::vector<std::string> random_session(const FuzzFolder& folder, uint64_t seed, size_t steps,
                                        std::optional<Failure>& failure) {
  folder.reset();
  Session session(folder);
  Rng rng(seed);
  std::vector<std::string> lines;
  failure.reset();
  for (size_t i = 0; i < steps; ++i) {
    lines.push_back(random_line(rng, session));
    if (std::string f = session.step(lines.back()); !f.empty()) {
      failure = Failure{i, f};
      break;
    }
  }
  return lines;
}

std::vector<std::string> shrink(const FuzzFolder& folder, std::vector<std::string> lines,
                                const Failure& failure) {
  const std::string kind = kind_of(failure.what);
  auto still_fails = [&](const std::vector<std::string>& candidate) {
    std::optional<Failure> f = run_session(folder, candidate);
    return f && kind_of(f->what) == kind;
  };
  lines.resize(std::min(lines.size(), failure.line + 1));
  // Delta debugging: drop ever smaller runs of lines while the failure stays.
  for (size_t chunk = std::max<size_t>(lines.size() / 2, 1);; chunk /= 2) {
    bool dropped = true;
    while (dropped) {
      dropped = false;
      for (size_t i = 0; i + chunk <= lines.size();) {
        std::vector<std::string> candidate(lines.begin(), lines.begin() + long(i));
        candidate.insert(candidate.end(), lines.begin() + long(i + chunk), lines.end());
        if (still_fails(candidate)) {
          lines = std::move(candidate);
          dropped = true;
        } else {
          i += chunk;
        }
      }
    }
    if (chunk == 1) break;
  }
  return lines;
}

}  // namespace welkin::editor::fuzz
