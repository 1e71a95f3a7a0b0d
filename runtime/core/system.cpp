#include "welkin/core/system.h"

#include <algorithm>

#include "welkin/core/error.h"
#include "welkin/core/world.h"

namespace welkin {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::update: return "update";
    case Phase::pre_render: return "pre-render";
    case Phase::render: return "render";
  }
  return "?";
}

void Scheduler::add(SystemDesc s) {
  for (const auto& existing : systems_)
    if (existing.name == s.name) throw Error("system '" + s.name + "' registered twice");
  // Keep systems sorted by order; equal orders stay in registration order.
  auto at = std::upper_bound(systems_.begin(), systems_.end(), s.order,
                             [](int order, const SystemDesc& other) { return order < other.order; });
  systems_.insert(at, std::move(s));
}

std::vector<std::string> Scheduler::run(Phase phase, SystemContext& ctx) {
  std::vector<std::string> ran;
  for (auto& s : systems_) {
    if (s.phase != phase) continue;
    std::vector<TypeId> query = s.reads;
    query.insert(query.end(), s.writes.begin(), s.writes.end());
    if (!ctx.world.registry().any_match(query)) continue;
    if (ctx.entering_system) ctx.entering_system(s.name);
    s.run(ctx);
    ran.push_back(s.name);
  }
  return ran;
}

}  // namespace welkin
