#include "welkin/assets/asset_cache.h"

#include "welkin/core/error.h"

namespace welkin::assets {

namespace fs = std::filesystem;

std::shared_ptr<const Model> AssetCache::load(const std::string& path) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  if (ec) throw Error(ErrorInfo{.file = path, .expected = "an existing glTF file", .found = ec.message()});
  const auto mtime = fs::last_write_time(canonical, ec);
  const uintmax_t size = ec ? 0 : fs::file_size(canonical, ec);
  const std::string key = canonical.string();
  {
    std::lock_guard lock(mutex_);
    auto it = entries_.find(key);
    if (it != entries_.end() && it->second.mtime == mtime && it->second.size == size) return it->second.model;
  }
  // The path as the caller wrote it names the file in errors; the canonical one keys the cache.
  auto model = std::make_shared<const Model>(load_gltf(path, options_));
  std::lock_guard lock(mutex_);
  entries_[key] = Entry{mtime, size, model};
  ++loads_;
  return model;
}

size_t AssetCache::evict_unused() {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->second.model.use_count() == 1) {
      it = entries_.erase(it);
      ++n;
    } else {
      ++it;
    }
  }
  return n;
}

void AssetCache::clear() {
  std::lock_guard lock(mutex_);
  entries_.clear();
}

size_t AssetCache::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

size_t AssetCache::load_count() const {
  std::lock_guard lock(mutex_);
  return loads_;
}

}  // namespace welkin::assets
