#include "welkin/core/registry.h"

#include <algorithm>
#include <cstring>

#include "welkin/core/error.h"

namespace welkin {

ComponentPool::ComponentPool(const TypeDesc& type) : type_(type) {}

ComponentPool::~ComponentPool() {
  for (size_t i = 0; i < dense_.size(); ++i) type_.ops.destroy(at(i));
  ::operator delete(data_, std::align_val_t(type_.align));
}

bool ComponentPool::contains(Entity e) const {
  return e.index < sparse_.size() && sparse_[e.index] != kAbsent && dense_[sparse_[e.index]] == e;
}

void ComponentPool::grow() {
  size_t cap = std::max<size_t>(8, capacity_ * 2);
  auto* fresh = static_cast<std::byte*>(::operator new(cap * type_.size, std::align_val_t(type_.align)));
  for (size_t i = 0; i < dense_.size(); ++i) {
    type_.ops.move_construct(fresh + i * type_.size, at(i));
    type_.ops.destroy(at(i));
  }
  ::operator delete(data_, std::align_val_t(type_.align));
  data_ = fresh;
  capacity_ = cap;
}

void* ComponentPool::emplace(Entity e) {
  if (contains(e)) return get(e);
  if (dense_.size() == capacity_) grow();
  if (e.index >= sparse_.size()) sparse_.resize(e.index + 1, kAbsent);
  sparse_[e.index] = uint32_t(dense_.size());
  dense_.push_back(e);
  void* p = at(dense_.size() - 1);
  type_.ops.construct(p);
  return p;
}

void* ComponentPool::get(Entity e) { return contains(e) ? at(sparse_[e.index]) : nullptr; }
const void* ComponentPool::get(Entity e) const {
  return contains(e) ? data_ + sparse_[e.index] * type_.size : nullptr;
}

void ComponentPool::remove(Entity e) {
  if (!contains(e)) return;
  uint32_t i = sparse_[e.index];
  uint32_t last = uint32_t(dense_.size() - 1);
  if (i != last) {
    type_.ops.move_assign(at(i), at(last));
    dense_[i] = dense_[last];
    sparse_[dense_[i].index] = i;
  }
  type_.ops.destroy(at(last));
  dense_.pop_back();
  sparse_[e.index] = kAbsent;
}

Registry::~Registry() = default;

Entity Registry::create() {
  uint32_t index;
  if (!free_.empty()) {
    index = free_.back();
    free_.pop_back();
  } else {
    index = uint32_t(versions_.size());
    versions_.push_back(0);
    alive_flags_.push_back(false);
  }
  alive_flags_[index] = true;
  ++alive_;
  return Entity{index, versions_[index]};
}

bool Registry::valid(Entity e) const {
  return e.index < versions_.size() && alive_flags_[e.index] && versions_[e.index] == e.version;
}

void Registry::destroy(Entity e) {
  if (!valid(e)) return;
  for (auto& [id, p] : pools_) p->remove(e);
  alive_flags_[e.index] = false;
  ++versions_[e.index];
  free_.push_back(e.index);
  --alive_;
}

std::vector<Entity> Registry::entities() const {
  std::vector<Entity> out;
  for (uint32_t i = 0; i < versions_.size(); ++i)
    if (alive_flags_[i]) out.push_back(Entity{i, versions_[i]});
  return out;
}

void* Registry::emplace(Entity e, const TypeDesc& type) {
  if (!valid(e)) throw Error("emplace on a destroyed entity");
  auto& p = pools_[type.id];
  if (!p) {
    p = std::make_unique<ComponentPool>(type);
    pool_order_.push_back(type.id);
  } else if (p->type().size != type.size || p->type().name != type.name) {
    throw Error(
        ErrorInfo{.message = "component '" + type.name + "' registered twice with different layouts"});
  }
  return p->emplace(e);
}

ComponentPool* Registry::pool(TypeId id) {
  auto it = pools_.find(id);
  return it == pools_.end() ? nullptr : it->second.get();
}
const ComponentPool* Registry::pool(TypeId id) const {
  auto it = pools_.find(id);
  return it == pools_.end() ? nullptr : it->second.get();
}

void* Registry::get(Entity e, TypeId id) {
  auto* p = pool(id);
  return p && valid(e) ? p->get(e) : nullptr;
}
const void* Registry::get(Entity e, TypeId id) const {
  auto* p = pool(id);
  return p && valid(e) ? p->get(e) : nullptr;
}
bool Registry::has(Entity e, TypeId id) const { return get(e, id) != nullptr; }
void Registry::remove(Entity e, TypeId id) {
  if (auto* p = pool(id)) p->remove(e);
}

std::vector<const TypeDesc*> Registry::components_of(Entity e) const {
  std::vector<const TypeDesc*> out;
  for (TypeId id : pool_order_) {
    const ComponentPool* p = pool(id);
    if (p->contains(e)) out.push_back(&p->type());
  }
  return out;
}

bool Registry::any_match(std::span<const TypeId> ids) const {
  const ComponentPool* smallest = nullptr;
  for (TypeId id : ids) {
    const ComponentPool* p = pool(id);
    if (!p || p->empty()) return false;
    if (!smallest || p->size() < smallest->size()) smallest = p;
  }
  if (!smallest) return true;  // an empty query matches the world itself
  for (Entity e : smallest->entities()) {
    bool all = true;
    for (TypeId id : ids) all = all && pool(id)->contains(e);
    if (all) return true;
  }
  return false;
}

}  // namespace welkin
