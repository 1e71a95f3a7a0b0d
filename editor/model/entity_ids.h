#pragma once
// Editor ids for entities. A registry handle changes when an entity is destroyed and re-created
// (undo of a removal), so commands name entities by an id that the editor re-binds instead.
#include <cstdint>
#include <unordered_map>

#include "welkin/core/registry.h"

namespace welkin::editor {

using EntityId = uint64_t;
inline constexpr EntityId kNoEntity = 0;

class EntityIds {
 public:
  // The id of `e`, assigning a fresh one the first time the editor sees it.
  EntityId id_of(Entity e);
  // A fresh id bound to nothing yet (an entity an edit is about to create).
  EntityId reserve() { return next_++; }
  // The live handle of `id`, or a null entity.
  Entity entity_of(EntityId id) const;
  // Points `id` at a (re-created) entity.
  void bind(EntityId id, Entity e);
  void unbind(EntityId id);
  // Forgets destroyed entities and names entities created behind the editor's back (by systems).
  void sync(const Registry& registry);
  void clear();

 private:
  std::unordered_map<EntityId, Entity> entities_;
  std::unordered_map<Entity, EntityId> ids_;
  EntityId next_ = 1;
};

}  // namespace welkin::editor
