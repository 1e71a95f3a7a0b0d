#include "welkin/core/world.h"

#include "welkin/scene/shared_state.h"

namespace welkin {

const ModuleDefinition& builtin_module_definition();  // runtime/builtin_module.cpp

World::World() : modules_(*this), registry_(std::make_unique<Registry>()) {
  modules_.add_static(builtin_module_definition());
  modules_.load("core");
}

World::~World() = default;

std::vector<std::string> World::update(const FrameInfo& frame) {
  SystemContext ctx{.world = *this, .frame = frame};
  // The shared state is written anew by every update (welkin/scene/shared_state.h).
  clear_shared_state(*this);
  auto ran = scheduler_.run(Phase::update, ctx);
  auto pre = scheduler_.run(Phase::pre_render, ctx);
  ran.insert(ran.end(), pre.begin(), pre.end());
  return ran;
}

}  // namespace welkin
