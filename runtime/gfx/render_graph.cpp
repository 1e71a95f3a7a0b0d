#include "welkin/gfx/render_graph.h"

#include <algorithm>

#include "welkin/core/error.h"

namespace welkin {

ResourceHandle PassBuilder::create(const std::string& name, const TextureDesc& desc) {
  return write(graph_.create(name, desc));
}

ResourceHandle PassBuilder::read(ResourceHandle h) {
  if (!h.valid() || h.index >= graph_.resources_.size())
    throw Error("render graph: pass '" + graph_.passes_[pass_].name + "' reads an invalid resource");
  graph_.passes_[pass_].reads.push_back(h.index);
  return h;
}

ResourceHandle PassBuilder::write(ResourceHandle h) {
  if (!h.valid() || h.index >= graph_.resources_.size())
    throw Error("render graph: pass '" + graph_.passes_[pass_].name + "' writes an invalid resource");
  graph_.passes_[pass_].writes.push_back(h.index);
  return h;
}

void PassBuilder::side_effect() { graph_.passes_[pass_].side_effect = true; }

Texture& PassContext::texture(ResourceHandle h) const {
  auto& r = graph_.resources_.at(h.index);
  if (!r.texture)
    throw Error("render graph: pass '" + name_ + "' uses '" + r.name + "' which it did not declare");
  return *r.texture;
}

ResourceHandle RenderGraph::import(const std::string& name, Texture& texture) {
  resources_.push_back({.name = name, .desc = texture.desc(), .texture = &texture, .imported = true});
  return ResourceHandle{uint32_t(resources_.size() - 1)};
}

ResourceHandle RenderGraph::create(const std::string& name, const TextureDesc& desc) {
  resources_.push_back({.name = name, .desc = desc});
  return ResourceHandle{uint32_t(resources_.size() - 1)};
}

void RenderGraph::publish(GraphKey key, ResourceHandle h) {
  if (!h.valid() || h.index >= resources_.size())
    throw Error("render graph: publishing an invalid resource as '" + std::string(key.name) + "'");
  blackboard_.insert_or_assign(std::string(key.name), h);
}

ResourceHandle RenderGraph::published(GraphKey key) const {
  auto it = blackboard_.find(key.name);
  return it == blackboard_.end() ? ResourceHandle{} : it->second;
}

void RenderGraph::add_pass(const std::string& name, const SetupFn& setup, ExecuteFn execute) {
  passes_.push_back({.name = name, .system = system_, .execute = std::move(execute)});
  PassBuilder b(*this, uint32_t(passes_.size() - 1));
  setup(b);
  compiled_ = false;
}

void RenderGraph::present(ResourceHandle h) {
  if (!h.valid() || h.index >= resources_.size()) throw Error("render graph: presenting an invalid resource");
  presented_.push_back(h.index);
}

std::vector<std::string> RenderGraph::compile() {
  // Walk backwards from the presented targets: a pass lives if it writes something still needed;
  // what it reads becomes needed by the passes before it.
  std::vector<bool> needed(resources_.size(), false);
  for (uint32_t r : presented_) needed[r] = true;
  for (int p = int(passes_.size()) - 1; p >= 0; --p) {
    Pass& pass = passes_[p];
    pass.alive = pass.side_effect;
    for (uint32_t w : pass.writes) pass.alive = pass.alive || needed[w];
    if (!pass.alive) continue;
    for (uint32_t r : pass.reads) needed[r] = true;
  }
  for (auto& r : resources_) r.first_use = r.last_use = -1;
  std::vector<std::string> alive;
  for (int p = 0; p < int(passes_.size()); ++p) {
    if (!passes_[p].alive) continue;
    alive.push_back(passes_[p].name);
    auto touch = [&](uint32_t i) {
      auto& r = resources_[i];
      if (r.first_use < 0) r.first_use = p;
      r.last_use = p;
    };
    for (uint32_t i : passes_[p].reads) touch(i);
    for (uint32_t i : passes_[p].writes) touch(i);
  }
  for (uint32_t i : presented_) resources_[i].last_use = int(passes_.size());  // outlive the frame
  compiled_ = true;
  return alive;
}

std::vector<std::string> RenderGraph::culled_passes() const {
  std::vector<std::string> out;
  for (const auto& p : passes_)
    if (!p.alive) out.push_back(p.name);
  return out;
}

void RenderGraph::execute(GraphBackend& backend) {
  if (!compiled_) compile();
  timings_.clear();
  backend.begin_frame();
  for (int p = 0; p < int(passes_.size()); ++p) {
    Pass& pass = passes_[p];
    if (!pass.alive) continue;
    // Transients are acquired just before their first use and returned right after their last,
    // so later passes can reuse the same memory.
    for (const std::vector<uint32_t>* used : {&pass.reads, &pass.writes})
      for (uint32_t i : *used) {
        auto& r = resources_[i];
        if (!r.imported && !r.texture && r.first_use == p) r.texture = backend.acquire(r.desc);
      }
    auto t0 = std::chrono::steady_clock::now();
    backend.begin_pass(pass.name);
    PassContext ctx(*this, pass.name);
    pass.execute(ctx);
    backend.end_pass();
    double cpu = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    timings_.push_back({pass.name, pass.system, 0.0, cpu});
    for (auto& r : resources_)
      if (!r.imported && r.texture && r.last_use == p) {
        backend.release(r.texture);
        r.texture = nullptr;
      }
  }
  std::vector<double> gpu = backend.resolve_gpu_times();
  for (size_t i = 0; i < timings_.size() && i < gpu.size(); ++i) timings_[i].gpu_ms = gpu[i];
}

}  // namespace welkin
