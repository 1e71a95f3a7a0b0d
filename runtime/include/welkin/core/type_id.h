#pragma once
// Component ids are a hash of the registered name, so the same component has the same id in the
// executable and in every plugin (a per-library template counter would not be).
#include <cstdint>
#include <string_view>

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

constexpr TypeId type_id_of_name(std::string_view name) { return fnv1a_64(name); }

// Components declare `static constexpr std::string_view kTypeName = "module.Name";`
template <class T> constexpr TypeId type_id() { return type_id_of_name(T::kTypeName); }

}  // namespace welkin
