#pragma once
// Component ids are a hash of the registered name, so the same component has the same id in the
// executable and in every plugin (a per-library template counter would not be).
#include <cstdint>
#include <string_view>
#include <type_traits>

namespace welkin {

using TypeId = uint64_t;

// FNV-1a 64 of `bytes`, continuing from `h` (so that several pieces hash as one stream).
inline constexpr uint64_t kFnv1aOffset = 14695981039346656037ull;
constexpr uint64_t fnv1a_64(std::string_view bytes, uint64_t h = kFnv1aOffset) {
  for (char c : bytes) {
    h ^= uint8_t(c);
    h *= 1099511628211ull;
  }
  return h;
}

// The same over a value's bytes (a type without padding, so that every byte is defined).
template <class T> uint64_t fnv1a_64_of(const T& value, uint64_t h = kFnv1aOffset) {
  static_assert(std::is_trivially_copyable_v<T>);
  return fnv1a_64(std::string_view(reinterpret_cast<const char*>(&value), sizeof value), h);
}

constexpr TypeId type_id_of_name(std::string_view name) { return fnv1a_64(name); }

// Components declare `static constexpr std::string_view kTypeName = "module.Name";`
template <class T> constexpr TypeId type_id() { return type_id_of_name(T::kTypeName); }

}  // namespace welkin
