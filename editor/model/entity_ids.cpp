#include "model/entity_ids.h"

#include <vector>

namespace welkin::editor {

EntityId EntityIds::id_of(Entity e) {
  if (e.is_null()) return kNoEntity;
  if (auto it = ids_.find(e); it != ids_.end()) return it->second;
  EntityId id = next_++;
  bind(id, e);
  return id;
}

Entity EntityIds::entity_of(EntityId id) const {
  auto it = entities_.find(id);
  return it == entities_.end() ? kNullEntity : it->second;
}

void EntityIds::bind(EntityId id, Entity e) {
  unbind(id);
  entities_[id] = e;
  ids_[e] = id;
  if (id >= next_) next_ = id + 1;
}

void EntityIds::unbind(EntityId id) {
  if (auto it = entities_.find(id); it != entities_.end()) {
    ids_.erase(it->second);
    entities_.erase(it);
  }
}

void EntityIds::sync(const Registry& registry) {
  std::vector<EntityId> dead;
  for (const auto& [id, e] : entities_)
    if (!registry.valid(e)) dead.push_back(id);
  for (EntityId id : dead) unbind(id);
  for (Entity e : registry.entities()) id_of(e);
}

void EntityIds::clear() {
  entities_.clear();
  ids_.clear();
}

}  // namespace welkin::editor
