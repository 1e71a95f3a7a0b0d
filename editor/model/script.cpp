#include "model/script.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "model/map_painting.h"
#include "model/preset_actions.h"
#include "model/sequence.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

using nlohmann::json;

namespace {

constexpr uint64_t kMaxScriptBytes = 16u << 20;  // an editor script file

[[noreturn]] void line_error(const ScriptLine& line, const std::string& message) {
  throw Error(ErrorInfo{.file = line.where(), .message = message});
}

std::string expand_variables(const std::string& raw, const std::string& where) {
  std::string out;
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '$') {
      out += raw[i];
      continue;
    }
    if (i + 1 < raw.size() && raw[i + 1] == '$') {
      out += '$';
      ++i;
      continue;
    }
    size_t start = i + 1, end = start;
    bool braced = start < raw.size() && raw[start] == '{';
    if (braced) {
      end = raw.find('}', start);
      if (end == std::string::npos) throw Error(ErrorInfo{.file = where, .message = "unterminated ${ in variable"});
      ++start;
    } else {
      while (end < raw.size() && (std::isalnum(static_cast<unsigned char>(raw[end])) || raw[end] == '_')) ++end;
    }
    std::string name = raw.substr(start, end - start);
    if (name.empty()) throw Error(ErrorInfo{.file = where, .message = "'$' without a variable name (write $$ for a dollar)"});
    const char* value = std::getenv(name.c_str());
    if (!value) throw Error(ErrorInfo{.file = where, .message = "environment variable " + name + " is not set"});
    out += value;
    i = braced ? end : end - 1;
  }
  return out;
}

// Splits `text` into words; quotes group, '#' outside quotes ends the line.
void split_words(ScriptLine& line) {
  const std::string& t = line.text;
  size_t i = 0;
  std::vector<std::string> words;
  std::vector<size_t> offsets;
  while (i < t.size()) {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    if (i >= t.size() || t[i] == '#') break;
    offsets.push_back(i);
    std::string word;
    if (t[i] == '"') {
      ++i;
      bool closed = false;
      while (i < t.size()) {
        char c = t[i++];
        if (c == '\\' && i < t.size()) word += t[i++];
        else if (c == '"') { closed = true; break; }
        else word += c;
      }
      if (!closed) line_error(line, "unterminated quote");
    } else {
      while (i < t.size() && !std::isspace(static_cast<unsigned char>(t[i]))) word += t[i++];
    }
    words.push_back(std::move(word));
  }
  // Drop a trailing comment from the text so tail() never returns it.
  if (i < t.size() && t[i] == '#') line.text = t.substr(0, i);
  if (words.empty()) return;
  line.verb = words.front();
  line.args.assign(words.begin() + 1, words.end());
  line.arg_offsets.assign(offsets.begin() + 1, offsets.end());
}

void require_args(const ScriptLine& line, size_t min, size_t max, const char* usage) {
  if (line.args.size() < min || line.args.size() > max) line_error(line, std::string("usage: ") + usage);
}

// A value: JSON when it parses, else the words as a string (bare enum names, entity names).
json parse_value(const ScriptLine& line, size_t first) {
  std::string text = line.tail(first);
  json j = json::parse(text, nullptr, false);
  if (!j.is_discarded()) return j;
  if (line.args.size() == first + 1) return line.args[first];
  return text;
}

double parse_number(const ScriptLine& line, size_t i, const char* what) {
  const std::string& s = line.args[i];
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v)) line_error(line, std::string("expected ") + what + ", found '" + s + "'");
  return v;
}

// An element of an array (a layer's index): decimal digits only.
size_t element_index(const ScriptLine& line, size_t i) {
  const std::string& s = line.args[i];
  if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
    line_error(line, "expected an element index (0, 1, ...), found '" + s + "'");
  return size_t(std::stoul(s));
}

// Numbers match within a relative 1e-6 (the value went through a float).
bool values_match(const json& a, const json& b) {
  if (a.is_number() && b.is_number()) {
    double x = a.get<double>(), y = b.get<double>();
    return std::abs(x - y) <= 1e-6 * std::max({1.0, std::abs(x), std::abs(y)});
  }
  if (a.is_array() && b.is_array()) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (!values_match(a[i], b[i])) return false;
    return true;
  }
  if (a.is_object() && b.is_object()) {
    if (a.size() != b.size()) return false;
    for (auto it = a.begin(); it != a.end(); ++it)
      if (!b.contains(it.key()) || !values_match(it.value(), b[it.key()])) return false;
    return true;
  }
  return a == b;
}

EntityId selected_or_named(EditorDocument& doc, const ScriptLine& line, size_t arg) {
  if (line.args.size() > arg) {
    EntityId id = doc.find_by_name(line.args[arg]);
    if (id == kNoEntity) line_error(line, "no entity named '" + line.args[arg] + "'");
    return id;
  }
  if (doc.selected() == kNoEntity) line_error(line, "no entity is selected (use: select NAME)");
  return doc.selected();
}

// The entity a component verb acts on: the selected one when it has the component, else the first.
EntityId target_for(EditorDocument& doc, const ScriptLine& line, const std::string& component) {
  doc.require_component(component);
  EntityId id = doc.entity_with(component);
  if (id == kNoEntity) line_error(line, "no entity has a " + component + " component (use: add-component)");
  return id;
}

const PresetFile& find_preset(PresetLibrary& presets, const ScriptLine& line, const std::string& module, const std::string& name) {
  const PresetFile* p = presets.find(module, name);
  if (!p) {
    std::string known;
    for (const PresetFile& q : presets.presets())
      if (q.module == module) known += (known.empty() ? "" : ", ") + q.name;
    line_error(line, "no preset '" + name + "' in module '" + module + "'" + (known.empty() ? "" : " (presets: " + known + ")"));
  }
  if (!p->ok()) line_error(line, "preset " + module + "/" + name + " does not load: " + format_error(*p->error));
  return *p;
}

// The entity a preset goes to: one with its component, else the selected entity (which gains it).
EntityId preset_target(EditorDocument& doc, const ScriptLine& line, const std::string& component) {
  doc.require_component(component);
  EntityId id = doc.entity_with(component);
  if (id == kNoEntity) id = doc.selected();
  if (id == kNoEntity) line_error(line, "no entity has a " + component + " component and none is selected");
  return id;
}

std::string track_entity_name(EditorDocument& doc, EntityId id) {
  Entity e = doc.entity(id);
  const Name* n = doc.world().registry().get<Name>(e);
  return n ? n->value : std::string();
}

// The preset verbs (apply, revert, blend, save, load, rename, diff, rescan); false for another verb.
bool run_preset_verb(EditorDocument& doc, PresetLibrary& presets, const ScriptLine& line,
                     std::string& output) {
  const std::string& v = line.verb;
  const auto& a = line.args;
  if (v == "apply-preset") {
    require_args(line, 2, 3, "apply-preset MODULE NAME [ELEMENT]");
    const PresetFile& p = find_preset(presets, line, a[0], a[1]);
    if (a.size() == 3)
      apply_preset_to_element(doc, presets, p, preset_target(doc, line, p.component), element_index(line, 2));
    else
      apply_preset(doc, presets, p, preset_target(doc, line, p.component));
  } else if (v == "revert-preset") {
    require_args(line, 2, 2, "revert-preset MODULE NAME");
    const PresetFile& p = find_preset(presets, line, a[0], a[1]);
    revert_to_preset_file(doc, presets, p, preset_target(doc, line, p.component));
  } else if (v == "blend-presets") {
    require_args(line, 4, 4, "blend-presets MODULE A B T");
    const PresetFile& pa = find_preset(presets, line, a[0], a[1]);
    const PresetFile& pb = find_preset(presets, line, a[0], a[2]);
    blend_presets(doc, presets, pa, pb, parse_number(line, 3, "a blend factor in [0, 1]"),
                  preset_target(doc, line, pa.component));
  } else if (v == "save-preset") {
    require_args(line, 2, 3, "save-preset MODULE NAME [ELEMENT]");
    PresetFile p = find_preset(presets, line, a[0], a[1]);
    if (a.size() == 3)
      save_preset_element(doc, presets, p, target_for(doc, line, p.component), element_index(line, 2));
    else
      save_preset(doc, presets, p, target_for(doc, line, p.component));
  } else if (v == "save-preset-as") {
    require_args(line, 2, 2, "save-preset-as COMPONENT PATH");
    save_preset_as(doc, presets, a[0], target_for(doc, line, a[0]), a[1]);
  } else if (v == "load-preset") {
    require_args(line, 2, 2, "load-preset COMPONENT PATH");
    PresetFile p = presets.read_for_component(a[0], a[1]);
    if (!p.ok()) line_error(line, "preset does not load: " + format_error(*p.error));
    apply_preset(doc, presets, p, preset_target(doc, line, a[0]));
  } else if (v == "rename-preset") {
    require_args(line, 3, 3, "rename-preset MODULE NAME NEW_NAME");
    presets.rename(find_preset(presets, line, a[0], a[1]), a[2]);
  } else if (v == "diff-preset") {
    require_args(line, 2, 3, "diff-preset MODULE NAME [ELEMENT]");
    const PresetFile& p = find_preset(presets, line, a[0], a[1]);
    const EntityId target = target_for(doc, line, p.component);
    auto fields = a.size() == 3 ? preset_element_differences(doc, presets, p, target, element_index(line, 2))
                                : preset_differences(doc, presets, p, target);
    output += a[0] + "/" + a[1] + " differs in " + std::to_string(fields.size()) + " field(s)";
    for (const auto& f : fields) output += " " + f;
    output += "\n";
  } else if (v == "rescan-presets") {
    require_args(line, 0, 0, "rescan-presets");
    presets.rescan();
  } else {
    return false;
  }
  return true;
}

}  // namespace

std::string ScriptLine::tail(size_t i) const {
  if (i >= arg_offsets.size()) return {};
  std::string s = text.substr(arg_offsets[i]);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

std::vector<ScriptLine> parse_script(const std::string& text, const std::string& file) {
  std::vector<ScriptLine> lines;
  std::istringstream in(text);
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    ScriptLine line{.file = file, .number = number};
    // Comments go before expansion, so a '$' in a comment is not an error.
    size_t first = raw.find_first_not_of(" \t");
    if (first == std::string::npos || raw[first] == '#') continue;
    line.text = expand_variables(raw, line.where());
    split_words(line);
    if (!line.verb.empty()) lines.push_back(std::move(line));
  }
  return lines;
}

std::vector<ScriptLine> load_script(const std::string& path) {
  return parse_script(read_file_text(path, kMaxScriptBytes), path);
}

bool run_document_verb(EditorDocument& doc, PresetLibrary& presets, const ScriptLine& line, std::string& output) {
  const std::string& v = line.verb;
  const auto& a = line.args;
  if (run_preset_verb(doc, presets, line, output)) return true;
  if (v == "load-scene") {
    require_args(line, 1, 1, "load-scene PATH");
    doc.load_scene(a[0]);
  } else if (v == "save-scene") {
    require_args(line, 1, 1, "save-scene PATH");
    doc.save_scene(a[0]);
  } else if (v == "new-scene") {
    require_args(line, 0, 0, "new-scene");
    doc.new_scene();
  } else if (v == "select") {
    require_args(line, 1, 1, "select NAME");
    doc.select(selected_or_named(doc, line, 0));
  } else if (v == "add-entity") {
    require_args(line, 1, 1, "add-entity NAME");
    doc.add_entity(a[0]);
  } else if (v == "remove-entity") {
    require_args(line, 0, 1, "remove-entity [NAME]");
    doc.remove_entity(selected_or_named(doc, line, 0));
  } else if (v == "rename-entity") {
    require_args(line, 1, 1, "rename-entity NEW_NAME");
    doc.rename_entity(selected_or_named(doc, line, 1), a[0]);
  } else if (v == "add-component") {
    require_args(line, 1, 1, "add-component COMPONENT");
    doc.add_component(selected_or_named(doc, line, 1), a[0]);
  } else if (v == "remove-component") {
    require_args(line, 1, 1, "remove-component COMPONENT");
    doc.remove_component(selected_or_named(doc, line, 1), a[0]);
  } else if (v == "set" || v == "expect" || v == "print") {
    require_args(line, v == "print" ? 1 : 2, v == "print" ? 1 : 1000, "set|expect COMPONENT/FIELD/PATH VALUE, print COMPONENT/FIELD/PATH");
    TrackTarget target = split_track_target(a[0]);
    EntityId id = target_for(doc, line, target.component);
    if (v == "set") {
      doc.set_field(id, target.component, target.path, parse_value(line, 1));
    } else {
      json actual = doc.get_field(id, target.component, target.path);
      if (v == "print") output += a[0] + " = " + actual.dump() + "\n";
      else if (!values_match(actual, parse_value(line, 1)))
        line_error(line, "expected " + a[0] + " = " + parse_value(line, 1).dump() + ", found " + actual.dump());
    }
  } else if (v == "undo" || v == "redo") {
    require_args(line, 0, 0, "undo | redo");
    if (!(v == "undo" ? doc.undo() : doc.redo())) line_error(line, "nothing to " + v);
  } else if (v == "key" || v == "unkey") {
    bool add = v == "key";
    require_args(line, add ? 3 : 2, add ? 1000 : 2, "key COMPONENT/FIELD/PATH TIME VALUE, unkey COMPONENT/FIELD/PATH TIME");
    TrackTarget target = split_track_target(a[0]);
    std::string entity = track_entity_name(doc, target_for(doc, line, target.component));
    double t = parse_number(line, 1, "a time in seconds");
    Sequence s = add ? with_key(doc.sequence(), entity, a[0], t, parse_value(line, 2))
                     : without_key(doc.sequence(), entity, a[0], t);
    doc.set_sequence(std::move(s), (add ? "Add key " : "Remove key ") + a[0]);
  } else if (v == "time") {
    require_args(line, 1, 1, "time SECONDS");
    for (const auto& problem : doc.preview_sequence(parse_number(line, 0, "a time in seconds"))) output += problem + "\n";
  } else if (v == "new-map") {
    require_args(line, 2, 2, "new-map COMPONENT/FIELD SIDE");
    const double side = parse_number(line, 1, "a side in texels");
    if (side < 1 || side > kMaxPaintedMapSide || side != std::floor(side))
      line_error(line, "expected a side of 1 to " + std::to_string(kMaxPaintedMapSide) + " texels, found '" + a[1] + "'");
    output += "new map " + new_map(doc, declared_map(doc, a[0]), int(side)) + "\n";
  } else if (v == "paint") {
    require_args(line, 6, 6, "paint COMPONENT/FIELD EAST_M NORTH_M RADIUS_M STRENGTH add|clear|reset");
    const MapBrush brush{.radius_m = parse_number(line, 3, "a radius in metres"), .strength = parse_number(line, 4, "a strength in [0, 1]"),
                         .mode = brush_mode_named(a[5])};
    if (!(brush.radius_m > 0.0) || brush.strength < 0.0 || brush.strength > 1.0)
      line_error(line, "expected a radius above 0 and a strength in [0, 1]");
    const glm::dvec3 at(parse_number(line, 1, "metres east"), parse_number(line, 2, "metres north"), 0.0);
    if (!paint_at(doc, declared_map(doc, a[0]), at, brush)) line_error(line, "the brush is off the map there");
  } else if (v == "expect-map") {
    require_args(line, 5, 5, "expect-map COMPONENT/FIELD EAST_M NORTH_M MIN MAX");
    const MapTarget target = find_map(doc, declared_map(doc, a[0]));
    if (target.file.empty()) line_error(line, a[0] + " names no map");
    const PaintedMap& map = doc.world().resource<PaintedMaps>().get(target.file);
    const glm::dvec2 uv = target.frame.uv(glm::dvec3(parse_number(line, 1, "metres east"), parse_number(line, 2, "metres north"), 0.0));
    if (uv.x < 0.0 || uv.y < 0.0 || uv.x >= 1.0 || uv.y >= 1.0) line_error(line, "that point is off the map");
    const int value = map.at(int(uv.x * map.side), int(uv.y * map.side));
    if (value < parse_number(line, 3, "a texel value") || value > parse_number(line, 4, "a texel value"))
      line_error(line, "expected the map texel in [" + a[3] + ", " + a[4] + "], found " + std::to_string(value));
  } else if (v == "load-sequence") {
    require_args(line, 1, 1, "load-sequence PATH");
    doc.load_sequence(a[0]);
  } else if (v == "save-sequence") {
    require_args(line, 1, 1, "save-sequence PATH");
    doc.save_sequence(a[0]);
  } else {
    return false;
  }
  return true;
}

bool run_session_verb(SessionGuard& guard, EditorDocument& doc, const ScriptLine& line) {
  const std::string& v = line.verb;
  const auto& a = line.args;
  if (v == "quit") {
    require_args(line, 0, 0, "quit");
    guard.request(GuardedAction::quit);
  } else if (v == "new-scene") {
    require_args(line, 0, 0, "new-scene");
    guard.request(GuardedAction::new_scene);
  } else if (v == "load-scene") {
    require_args(line, 1, 1, "load-scene PATH");
    guard.request(GuardedAction::open_scene, a[0]);
  } else if (v == "load-sequence") {
    require_args(line, 1, 1, "load-sequence PATH");
    guard.request(GuardedAction::open_sequence, a[0]);
  } else if (v == "save-scene") {
    require_args(line, 1, 1, "save-scene PATH");
    guard.request(GuardedAction::save_scene_as, a[0]);
  } else if (v == "answer") {
    require_args(line, 1, 1, "answer save|discard|cancel|overwrite|recover");
    std::optional<Answer> answer = answer_named(a[0]);
    if (!answer) line_error(line, "expected save, discard, cancel, overwrite or recover, found '" + a[0] + "'");
    guard.answer(*answer);
  } else if (v == "expect-prompt") {
    require_args(line, 1, 2, "expect-prompt none|unsaved|overwrite|recover [scene|sequence|scene+sequence]");
    const std::optional<Prompt>& p = guard.prompt();
    if (a[0] == "none") {
      if (p) line_error(line, "expected no prompt, found '" + prompt_text(*p) + "'");
    } else {
      std::optional<PromptKind> kind = prompt_kind_named(a[0]);
      if (!kind) line_error(line, "expected none, unsaved, overwrite or recover, found '" + a[0] + "'");
      if (!p || p->kind != *kind) line_error(line, "expected a " + a[0] + " prompt, found " + (p ? "'" + prompt_text(*p) + "'" : "none"));
      if (a.size() == 2) {
        const std::string parts = a[1] == "scene+sequence" ? "scene and sequence" : a[1];
        if (describe_parts(p->scene, p->sequence) != parts)
          line_error(line, "expected the prompt to name the " + parts + ", found '" + prompt_text(*p) + "'");
      }
    }
  } else if (v == "expect-dirty") {
    require_args(line, 2, 2, "expect-dirty scene|sequence yes|no");
    if (a[0] != "scene" && a[0] != "sequence") line_error(line, "expected scene or sequence, found '" + a[0] + "'");
    if (a[1] != "yes" && a[1] != "no") line_error(line, "expected yes or no, found '" + a[1] + "'");
    const bool dirty = a[0] == "scene" ? doc.scene_dirty() : doc.sequence_dirty();
    if (dirty != (a[1] == "yes"))
      line_error(line, "expected the " + a[0] + (a[1] == "yes" ? " to have unsaved changes, it has none" : " to be saved, it has unsaved changes"));
  } else if (v == "autosave-now") {
    require_args(line, 0, 0, "autosave-now");
    guard.autosave_now();
  } else {
    return false;
  }
  return true;
}

bool verb_allowed_during_prompt(const std::string& verb) {
  for (const char* v : {"answer", "expect-prompt", "expect-dirty", "wait", "crash", "screenshot", "screenshot-window"})
    if (verb == v) return true;
  return false;
}

const char* script_verbs_help() {
  return R"(Script verbs (one per line; '#' comments; "quotes" group words; $VAR from the environment):
  load-scene PATH | save-scene PATH | new-scene   ask first (a prompt) when they would lose or
                                      overwrite work, as the menus do
  select NAME | add-entity NAME | remove-entity [NAME] | rename-entity NEW_NAME
  add-component COMPONENT | remove-component COMPONENT          (on the selected entity)
  set COMPONENT/FIELD/PATH VALUE      value as JSON, else text; on the selected entity if it has
                                      the component, else the first that has it
  expect COMPONENT/FIELD/PATH VALUE   fails the script unless equal (numbers within 1e-6)
  print COMPONENT/FIELD/PATH
  apply-preset MODULE NAME [ELEMENT] | revert-preset MODULE NAME | blend-presets MODULE A B T
  save-preset MODULE NAME [ELEMENT] | save-preset-as COMPONENT PATH | load-preset COMPONENT PATH
  rename-preset MODULE NAME NEW_NAME | diff-preset MODULE NAME [ELEMENT] | rescan-presets
                                      NAME may be in a sub-folder (clouds genera/cirrus); a preset of
                                      one element (a cloud layer) is added as a new element, or with
                                      ELEMENT set over that one (layers/ELEMENT)
  undo | redo
  key COMPONENT/FIELD/PATH TIME VALUE | unkey COMPONENT/FIELD/PATH TIME | time SECONDS
  load-sequence PATH | save-sequence PATH
  new-map COMPONENT/FIELD SIDE        a neutral painted map beside the (saved) scene, named in the field
  paint COMPONENT/FIELD EAST_M NORTH_M RADIUS_M STRENGTH add|clear|reset   one brush stamp (undoable)
  expect-map COMPONENT/FIELD EAST_M NORTH_M MIN MAX   fails unless the texel there is in [MIN, MAX]
  screenshot PATH.png|PATH.exr        the viewport (tone-mapped PNG or linear HDR EXR)
  screenshot-window PATH.png          the whole editor window
  view X Y Z HEADING PITCH            place the viewport camera
  look-through-scene-camera on|off    fly the scene's camera instead of the editor's view
  map-brush COMPONENT/FIELD RADIUS_M STRENGTH add|clear|reset ALTITUDE_M   the viewport's map brush
  paint-viewport FX FY                one stamp where the viewport looks at (FX, FY) of its size from the
                                      top-left, at the brush's altitude
  fly FORWARD RIGHT UP LOOK_DX LOOK_DY SECONDS   one step of the fly camera (WASD/QE axes, mouse px)
  show-preset MODULE NAME             show a preset's details (file, error, differing fields)
  resize WIDTH HEIGHT | wait FRAMES
  clock run|pause                     the scene's clock (wind drift, time of day's time scale); paused
                                      at start, so that a still view settles
  moving-budget MS|off                moving frames render a smaller part of the viewport, sized so that
                                      a frame takes about MS (100 at start); off: the camera's
                                      moving_render_scale as set
  keep-settled FRAMES|off             a still view whose scene, view and clock stay the same for FRAMES
                                      frames (24 at start) shows its last frame instead of rendering
  measure-frames N [still | fly SPEED_M_S TURN_DEG_S]   hold the view (still, the default) or fly it
                                      (forward at SPEED, the heading turning at TURN, per second of wall
                                      time) for N frames, then print their frame times (mean, median,
                                      p90, fps), the load average and the passes' mean GPU times
  quit                                asks first when the scene or sequence has unsaved changes;
                                      a script whose last line is an unanswered quit quits without saving
  answer save|discard|cancel          the unsaved-changes prompt (save writes to the files they came from)
  answer overwrite|cancel             the save-as prompt for a file that exists
  answer recover|discard              the prompt at start offering the last session's autosave
  expect-prompt none|unsaved|overwrite|recover [scene|sequence|scene+sequence]   fails unless that
                                      prompt waits (naming those parts); while one waits only answer,
                                      expect-*, wait, crash and screenshots run
  expect-dirty scene|sequence yes|no  fails unless that part has (yes) or lacks (no) unsaved changes
  close-window                        as the window's close button: the next frame asks like quit
  autosave-now                        write the autosave now (normally 30 s after an unsaved edit)
  crash                               exit at once with status 70, as a crash would: no prompt, no
                                      cleanup, the autosave left behind (to test recovery)
)";
}

}  // namespace welkin::editor
