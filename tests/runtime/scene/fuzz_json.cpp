// libFuzzer target over the JSON readers that take user files: scenes, sequences and presets (a
// preset is a component's fields: core.DirectionalLight, core.DebugShape). The first byte picks the reader, the rest is the document. Only
// welkin::Error may come out; a crash, a leak, a hang or unbounded memory is a finding.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"
#include "welkin/scene/sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int reader = data[0] % 4;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const nlohmann::json doc = welkin::parse_json_text(text, "fuzz.json");
    if (reader == 0) {
      welkin::World world;  // core components only: a module's component is an Error
      welkin::load_scene(world, doc, "fuzz.json");
      (void)welkin::save_scene(world).dump();
    } else if (reader == 1) {
      const welkin::Sequence s = welkin::parse_sequence(doc, "fuzz.sequence.json");
      for (const welkin::Track& t : s.tracks)
        for (double at : {-1.0, 0.0, 0.5 * s.duration_s, s.duration_s, 1e300}) (void)welkin::evaluate_track(t, at);
    } else if (reader == 2) {
      welkin::DirectionalLight light;  // the component the shipped core presets hold
      welkin::object_from_json(welkin::type_desc<welkin::DirectionalLight>(), &light, doc);
    } else {
      welkin::DebugShape shape;  // enums, vectors, ranges and cross-field checks
      welkin::object_from_json(welkin::type_desc<welkin::DebugShape>(), &shape, doc);
    }
  } catch (const welkin::Error&) {
  }
  return 0;
}
