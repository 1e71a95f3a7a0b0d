#include "welkin/core/system.h"

#include <algorithm>

#include "welkin/core/error.h"
#include "welkin/core/world.h"

namespace welkin {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::update:
      return "update";
    case Phase::pre_render:
      return "pre-render";
    case Phase::render:
      return "render";
  }
  return "?";
}

const char* stage_name(Stage s) {
  switch (s) {
    case Stage::simulate:
      return "simulate";
    case Stage::complete_shared_state:
      return "complete_shared_state";
    case Stage::prepare:
      return "prepare";
    case Stage::tables:
      return "tables";
    case Stage::light_maps:
      return "light_maps";
    case Stage::background:
      return "background";
    case Stage::geometry:
      return "geometry";
    case Stage::aerial_perspective:
      return "aerial_perspective";
    case Stage::light_shafts:
      return "light_shafts";
    case Stage::clouds:
      return "clouds";
  }
  return "?";
}

Phase phase_of(Stage s) {
  if (s <= Stage::complete_shared_state) return Phase::update;
  if (s == Stage::prepare) return Phase::pre_render;
  return Phase::render;
}

void Scheduler::add(SystemDesc s) {
  for (const auto& existing : systems_)
    if (existing.name == s.name) throw Error("system '" + s.name + "' registered twice");
  systems_.push_back(std::move(s));
  resolved_ = false;
}

namespace {

// The systems of one stage (indices into `all`, in registration order) sorted so that each comes
// after those it names in `after` and before those in `before`: Kahn's algorithm, always taking the
// earliest registered of those ready.
std::vector<size_t> sort_stage(const std::vector<SystemDesc>& all, const std::vector<size_t>& stage) {
  const size_t n = stage.size();
  std::vector<std::vector<size_t>> followers(n);  // positions in `stage`
  std::vector<size_t> waiting(n, 0);
  // The position in the stage of a system named in `s`'s `list` ("after" or "before").
  auto locate = [&](const SystemDesc& s, const std::string& name, const char* list) {
    auto at = std::find_if(stage.begin(), stage.end(), [&](size_t k) { return all[k].name == name; });
    if (at != stage.end()) return size_t(at - stage.begin());
    auto elsewhere =
        std::find_if(all.begin(), all.end(), [&](const SystemDesc& d) { return d.name == name; });
    throw Error(ErrorInfo{.path = "system " + s.name + "/" + list,
                          .expected = std::string("a system of its stage, ") + stage_name(s.stage),
                          .found = elsewhere == all.end()
                                       ? "'" + name + "', which no system is named"
                                       : "'" + name + "', of stage " + stage_name(elsewhere->stage) +
                                             " (the stages' own order holds across stages)"});
  };
  auto precede = [&](size_t first, size_t then) {
    followers[first].push_back(then);
    ++waiting[then];
  };
  for (size_t i = 0; i < n; ++i) {
    const SystemDesc& s = all[stage[i]];
    for (const std::string& name : s.after) precede(locate(s, name, "after"), i);
    for (const std::string& name : s.before) precede(i, locate(s, name, "before"));
  }
  std::vector<size_t> out;
  std::vector<bool> done(n, false);
  while (out.size() < n) {
    size_t next = n;
    for (size_t i = 0; i < n && next == n; ++i)
      if (!done[i] && waiting[i] == 0) next = i;
    if (next == n) {
      std::string cycle;
      for (size_t i = 0; i < n; ++i)
        if (!done[i]) cycle += (cycle.empty() ? "" : ", ") + all[stage[i]].name;
      throw Error(std::string("systems of stage ") + stage_name(all[stage[0]].stage) +
                  " each wait for another (a cycle of `after`/`before` among " + cycle + ")");
    }
    done[next] = true;
    out.push_back(stage[next]);
    for (size_t f : followers[next]) --waiting[f];
  }
  return out;
}

}  // namespace

const std::vector<size_t>& Scheduler::order() {
  if (resolved_) return order_;
  std::vector<size_t> order;
  for (int s = 0; s <= int(Stage::clouds); ++s) {
    std::vector<size_t> stage;
    for (size_t i = 0; i < systems_.size(); ++i)
      if (systems_[i].stage == Stage(s)) stage.push_back(i);
    if (stage.empty()) continue;
    const std::vector<size_t> sorted = sort_stage(systems_, stage);
    order.insert(order.end(), sorted.begin(), sorted.end());
  }
  order_ = std::move(order);
  resolved_ = true;
  return order_;
}

std::vector<std::string> Scheduler::ordered_names(Phase phase) {
  std::vector<std::string> names;
  for (size_t i : order())
    if (phase_of(systems_[i].stage) == phase) names.push_back(systems_[i].name);
  return names;
}

std::vector<std::string> Scheduler::run(Phase phase, SystemContext& ctx) {
  std::vector<std::string> ran;
  for (size_t i : order()) {
    SystemDesc& s = systems_[i];
    if (phase_of(s.stage) != phase) continue;
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
