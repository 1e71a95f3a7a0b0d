#pragma once
// A world is one scene being simulated: its entities, the modules it loaded, their systems and
// the module-owned resources (GPU caches and the like) that live as long as the world.
#include <memory>
#include <string>
#include <typeindex>
#include <unordered_map>

#include "welkin/core/module.h"
#include "welkin/core/registry.h"
#include "welkin/core/system.h"

namespace welkin {

class World {
 public:
  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  Registry& registry() { return *registry_; }
  const Registry& registry() const { return *registry_; }
  Scheduler& scheduler() { return scheduler_; }
  ModuleHost& modules() { return modules_; }
  const ModuleHost& modules() const { return modules_; }

  // A resource owned by the world, created on first use. Keyed by T::kTypeName so a resource
  // type is the same in the executable and in plugins.
  template <class T> T& resource() {
    auto& slot = resources_[std::string(T::kTypeName)];
    if (!slot) slot = std::make_shared<T>();
    return *static_cast<T*>(slot.get());
  }
  template <class T> T* find_resource() {
    auto it = resources_.find(std::string(T::kTypeName));
    return it == resources_.end() ? nullptr : static_cast<T*>(it->second.get());
  }
  template <class T> const T* find_resource() const {
    auto it = resources_.find(std::string(T::kTypeName));
    return it == resources_.end() ? nullptr : static_cast<const T*>(it->second.get());
  }

  // Runs update and pre-render systems for one frame step.
  std::vector<std::string> update(const FrameInfo& frame);

 private:
  ModuleHost modules_;
  Scheduler scheduler_;
  std::unordered_map<std::string, std::shared_ptr<void>> resources_;
  std::unique_ptr<Registry> registry_;  // declared last: destroyed first, before resources
};

}  // namespace welkin
