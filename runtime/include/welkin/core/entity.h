#pragma once
// Entities are a 32-bit index into the component pools plus a 32-bit version that is bumped when
// the index is recycled, so a stale handle is detected instead of aliasing a new entity.
#include <cstdint>
#include <functional>

namespace welkin {

struct Entity {
  static constexpr uint32_t kNullIndex = 0xffffffffu;
  uint32_t index = kNullIndex;
  uint32_t version = 0;

  bool is_null() const { return index == kNullIndex; }
  friend bool operator==(Entity, Entity) = default;
};

inline constexpr Entity kNullEntity{};

}  // namespace welkin

template <> struct std::hash<welkin::Entity> {
  size_t operator()(welkin::Entity e) const noexcept {
    return std::hash<uint64_t>{}((uint64_t(e.version) << 32) | e.index);
  }
};
