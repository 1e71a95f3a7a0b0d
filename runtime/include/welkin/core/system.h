#pragma once
// Systems declare what they read and write and the phase they run in; the scheduler skips a
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

struct SystemContext {
  World& world;
  FrameInfo frame;
  RenderGraph* graph = nullptr;         // render phase only
  FrameTargets* targets = nullptr;  // render phase only: the frame's colour/depth handles
  // Called with each system's name before it runs (the renderer tells its graph whose passes follow).
  std::function<void(const std::string&)> entering_system;
};

struct SystemDesc {
  std::string name;
  Phase phase = Phase::update;
  // Within a phase, lower runs first (ties keep registration order): producers of per-frame inputs
  // (LUTs) negative, geometry 0, full-screen composites over the depth buffer positive.
  int order = 0;
  std::vector<TypeId> reads;   // required, read-only
  std::vector<TypeId> writes;  // required, written
  std::vector<TypeId> optional_reads;  // read if present; do not gate the system
  std::function<void(SystemContext&)> run;
};

class Scheduler {
 public:
  void add(SystemDesc system);
  // Runs the systems of a phase in registration order; returns the names of those that ran.
  std::vector<std::string> run(Phase phase, SystemContext& ctx);
  const std::vector<SystemDesc>& systems() const { return systems_; }

 private:
  std::vector<SystemDesc> systems_;
};

}  // namespace welkin
