#pragma once
// The entity registry: sparse-set pools keyed by stable component id. A pool stores components
// densely with their entities; views iterate the smallest pool of a query, so a query with an
// empty pool costs nothing (EnTT's design).
#include <cassert>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "welkin/core/entity.h"
#include "welkin/core/reflection.h"

namespace welkin {

// Type-erased sparse set of one component type.
class ComponentPool {
 public:
  explicit ComponentPool(const TypeDesc& type);
  ~ComponentPool();
  ComponentPool(const ComponentPool&) = delete;
  ComponentPool& operator=(const ComponentPool&) = delete;

  const TypeDesc& type() const { return type_; }
  size_t size() const { return dense_.size(); }
  bool empty() const { return dense_.empty(); }
  bool contains(Entity e) const;
  // Default-constructs (the declared defaults) and returns the component; replaces nothing.
  void* emplace(Entity e);
  void* get(Entity e);
  const void* get(Entity e) const;
  void remove(Entity e);
  std::span<const Entity> entities() const { return dense_; }
  void* at(size_t dense_index) { return data_ + dense_index * type_.size; }

 private:
  void grow();
  static constexpr uint32_t kAbsent = 0xffffffffu;
  const TypeDesc& type_;
  std::vector<Entity> dense_;
  std::vector<uint32_t> sparse_;  // entity index -> dense index
  std::byte* data_ = nullptr;
  size_t capacity_ = 0;
};

class Registry {
 public:
  Registry() = default;
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  Entity create();
  // Removes every component and retires the handle; the index is reused with a new version.
  void destroy(Entity e);
  bool valid(Entity e) const;
  size_t alive_count() const { return alive_; }
  // Entities in creation order (stable for saving).
  std::vector<Entity> entities() const;

  // Type-erased access, used by scene loading and the editor.
  void* emplace(Entity e, const TypeDesc& type);
  void* get(Entity e, TypeId id);
  const void* get(Entity e, TypeId id) const;
  bool has(Entity e, TypeId id) const;
  void remove(Entity e, TypeId id);
  ComponentPool* pool(TypeId id);
  const ComponentPool* pool(TypeId id) const;
  // Component types present on e, in registration order of their pools.
  std::vector<const TypeDesc*> components_of(Entity e) const;
  // Number of entities that have all the given components (cheap when one pool is empty).
  bool any_match(std::span<const TypeId> ids) const;

  template <class T> T& emplace(Entity e) { return *static_cast<T*>(emplace(e, type_desc<T>())); }
  template <class T> T* get(Entity e) { return static_cast<T*>(get(e, type_id<T>())); }
  template <class T> const T* get(Entity e) const { return static_cast<const T*>(get(e, type_id<T>())); }
  template <class T> bool has(Entity e) const { return has(e, type_id<T>()); }
  template <class T> void remove(Entity e) { remove(e, type_id<T>()); }

  // Calls fn(Entity, Cs&...) for every entity that has all of Cs.
  template <class... Cs, class Fn> void each(Fn&& fn) {
    ComponentPool* pools[] = {pool(type_id<Cs>())...};
    ComponentPool* smallest = nullptr;
    for (ComponentPool* p : pools) {
      if (!p || p->empty()) return;
      if (!smallest || p->size() < smallest->size()) smallest = p;
    }
    // Copy: fn may add components to other entities (never to this pool's order though).
    std::vector<Entity> list(smallest->entities().begin(), smallest->entities().end());
    for (Entity e : list) {
      if ((pools_contain(pools, e)))
        call_with(fn, e, pools, std::index_sequence_for<Cs...>{}, static_cast<Cs*>(nullptr)...);
    }
  }
  // First entity with all of Cs, or null.
  template <class... Cs> Entity first() {
    Entity found;
    each<Cs...>([&](Entity e, Cs&...) { if (found.is_null()) found = e; });
    return found;
  }

 private:
  template <size_t N> static bool pools_contain(ComponentPool* (&pools)[N], Entity e) {
    for (ComponentPool* p : pools)
      if (!p->contains(e)) return false;
    return true;
  }
  template <class Fn, size_t N, size_t... I, class... Cs>
  static void call_with(Fn& fn, Entity e, ComponentPool* (&pools)[N], std::index_sequence<I...>, Cs*...) {
    fn(e, *static_cast<Cs*>(pools[I]->get(e))...);
  }

  std::vector<uint32_t> versions_;
  std::vector<bool> alive_flags_;
  std::vector<uint32_t> free_;
  size_t alive_ = 0;
  std::unordered_map<TypeId, std::unique_ptr<ComponentPool>> pools_;
  std::vector<TypeId> pool_order_;
};

}  // namespace welkin
