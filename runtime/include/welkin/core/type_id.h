#pragma once
// Component ids are a hash of the registered name, so the same component has the same id in the
// executable and in every plugin (a per-library template counter would not be).
#include <cstdint>
#include <string_view>

namespace welkin {

using TypeId = uint64_t;

constexpr TypeId type_id_of_name(std::string_view name) {
  uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  for (char c : name) {
    h ^= uint8_t(c);
    h *= 1099511628211ull;
  }
  return h;
}

// Components declare `static constexpr std::string_view kTypeName = "module.Name";`
template <class T> constexpr TypeId type_id() { return type_id_of_name(T::kTypeName); }

}  // namespace welkin
