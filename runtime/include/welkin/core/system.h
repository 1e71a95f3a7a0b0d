#pragma once
// Systems declare what they read and write and the stage they run in; the scheduler skips a
// system whose required components match no entity, so a scene pays only for what it contains.
#include <functional>
#include <string>
#include <vector>

#include "welkin/core/type_id.h"

namespace welkin {

class World;
class RenderGraph;
struct FrameTargets;

enum class Phase { update, pre_render, render };
const char* phase_name(Phase p);

struct FrameInfo {
  double time_s = 0;   // time since the world started
  double dt_s = 0;     // this frame's step
  uint64_t index = 0;  // frame number
  // Rendered alone: nothing carried over from earlier frames that would change its pixels (temporal
  // reuse such as the clouds' upscaling). A sequence's frames are, so that any shard of a render
  // farm gives the same bytes for them.
  bool alone = false;
};

// The named stages of a frame, in the order they run (Bevy's system sets). A system names its stage;
// within a stage, `SystemDesc::after` orders it after other systems of the same stage, by name, and
// systems nothing orders keep the order they were registered in.
enum class Stage {
  // Phase::update
  simulate,               // what moves the scene on: the clock, sequences, the sun and moon's places
  complete_shared_state,  // what completes the shared state the first stage wrote (scene/shared_state.h)
  // Phase::pre_render
  prepare,
  // Phase::render
  tables,              // per-frame tables every material of the frame reads (the atmosphere's LUTs)
  light_maps,          // maps the light environment reads (the clouds' shadows)
  background,          // what lies behind all geometry (the sky)
  geometry,            // surfaces that write the depth (terrain, backdrops, debug shapes)
  aerial_perspective,  // the air between the camera and the geometry, laid over it
  light_shafts,        // the air's light darkened where the sun is hidden (god rays)
  clouds,              // the clouds, far ones first, composited over everything before
};
const char* stage_name(Stage s);
Phase phase_of(Stage s);

struct SystemContext {
  World& world;
  FrameInfo frame;
  RenderGraph* graph = nullptr;     // render phase only
  FrameTargets* targets = nullptr;  // render phase only: the frame's colour/depth handles
  // Called with each system's name before it runs (the renderer tells its graph whose passes follow).
  std::function<void(const std::string&)> entering_system;
};

struct SystemDesc {
  std::string name;
  Stage stage = Stage::simulate;
  // Systems of the same stage this one runs after (their names: "clouds.billboards"). A name no
  // system of the stage has is an error when the order is resolved, as is a cycle.
  std::vector<std::string> after;
  // Systems of the same stage this one runs before: how a module orders itself ahead of a module it
  // depends on, which cannot name it (weather.apply_report before timeofday's clock). Same errors.
  std::vector<std::string> before;
  std::vector<TypeId> reads;           // required, read-only
  std::vector<TypeId> writes;          // required, written
  std::vector<TypeId> optional_reads;  // read if present; do not gate the system
  std::function<void(SystemContext&)> run;
};

class Scheduler {
 public:
  void add(SystemDesc system);
  // Runs the systems of a phase in their order (order()); returns the names of those that ran.
  std::vector<std::string> run(Phase phase, SystemContext& ctx);
  // The names of a phase's systems in the order they run: by stage, then each after those it names
  // (a topological sort that keeps registration order where nothing constrains it). Throws Error on
  // a name that no system of the stage has, or on a cycle (naming the systems in it).
  std::vector<std::string> ordered_names(Phase phase);
  // The systems as registered.
  const std::vector<SystemDesc>& systems() const { return systems_; }

 private:
  const std::vector<size_t>& order();
  std::vector<SystemDesc> systems_;
  std::vector<size_t> order_;  // indices into systems_, once resolved
  bool resolved_ = false;
};

}  // namespace welkin
