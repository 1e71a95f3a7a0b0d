#include "session.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/module_paths.h"
#include "welkin/gfx/gpu_measure.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/json_fields.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& clouds_module();
}

namespace welkin::cli {

std::vector<std::string> module_search_dirs() {
  return welkin::module_search_dirs(WELKIN_MODULE_DIR_FROM_BIN, WELKIN_BUILD_MODULE_DIR, WELKIN_BUILD_BIN_DIR);
}

std::unique_ptr<World> make_world() {
  auto world = std::make_unique<World>();
  for (const auto& d : module_search_dirs()) world->modules().add_search_dir(d);
  // `probe` and `accuracy` call into the atmosphere and the clouds directly, so they are linked in;
  // registering the linked copies keeps one copy of their code in the process (they are still loaded
  // only on demand).
  world->modules().add_static(welkin::modules::atmosphere_module());
  world->modules().add_static(welkin::modules::clouds_module());
  return world;
}

void apply_assignment(World& world, const std::string& assignment) {
  auto eq = assignment.find('=');
  auto slash = assignment.find('/');
  if (eq == std::string::npos || slash == std::string::npos || slash > eq)
    throw Error(ErrorInfo{.path = "--set " + assignment, .expected = "component/field=value, e.g. core.Camera/vertical_fov_deg=45",
                          .found = "'" + assignment + "'"});
  std::string component = assignment.substr(0, slash);
  std::string path = assignment.substr(slash + 1, eq - slash - 1);
  std::string text = assignment.substr(eq + 1);
  world.modules().require_component(component);  // an unknown component's error names it alone
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    value = text;  // bare words are strings (enum names)
  }
  try {
    set_scene_field(world, component, path, value);
  } catch (const Error& e) {
    throw e.with_path_prefix("--set ");
  }
}

ImageF render_still(Renderer& renderer, int width, int height) {
  renderer.render_frame(FrameInfo{.index = 7, .alone = true}, width, height);
  return renderer.read_hdr();
}

std::pair<double, double> passes_cost(Renderer& renderer, const std::string& prefix, int width, int height, int frames) {
  for (int i = 0; i < 2; ++i) renderer.render_frame(FrameInfo{.index = uint64_t(i)}, width, height);
  CopyFloor copy(renderer.context().shaders, width, height);
  std::vector<double> pass, floor;
  for (int i = 0; i < frames; ++i) {
    const FrameResult fr = renderer.render_frame(FrameInfo{.time_s = i / 30.0, .dt_s = 1 / 30.0, .index = uint64_t(i + 2)}, width, height);
    double ms = 0.0;
    for (const auto& t : fr.timings)
      if (t.name.rfind(prefix, 0) == 0) ms += t.gpu_ms;
    pass.push_back(ms);
    floor.push_back(copy.measure_ms(5));
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  return {median(pass), median(floor)};
}

}  // namespace welkin::cli
