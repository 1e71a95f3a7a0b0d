#include "welkin/core/world.h"

namespace welkin {

const ModuleDefinition& builtin_module_definition();  // runtime/builtin_module.cpp

World::World() : modules_(*this), registry_(std::make_unique<Registry>()) {
  modules_.add_static(builtin_module_definition());
  modules_.load("core");
}

World::~World() = default;

std::vector<std::string> World::update(const FrameInfo& frame) {
  SystemContext ctx{.world = *this, .frame = frame};
  auto ran = scheduler_.run(Phase::update, ctx);
  auto pre = scheduler_.run(Phase::pre_render, ctx);
  ran.insert(ran.end(), pre.begin(), pre.end());
  return ran;
}

}  // namespace welkin
