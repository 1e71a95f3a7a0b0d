#pragma once
// Loaded models shared by everything that asks for the same file: keyed by canonical path and
// modification time, so an edited file is reloaded and a symlinked or relative path is not loaded twice.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "welkin/assets/gltf_loader.h"

namespace welkin::assets {

class AssetCache {
 public:
  explicit AssetCache(LoadOptions options = {}) : options_(std::move(options)) {}

  // Returns the cached model, or loads it (throws welkin::Error). Thread-safe; a load happens
  // outside the lock, so two threads asking for one new file may both load it (last one is kept).
  std::shared_ptr<const Model> load(const std::string& path);

  // Drops entries nobody else holds; returns how many were dropped.
  size_t evict_unused();
  void clear();
  size_t size() const;
  // Loads that actually read a file (not served from the cache), for tests and statistics.
  size_t load_count() const;

 private:
  struct Entry {
    std::filesystem::file_time_type mtime;
    uintmax_t size = 0;
    std::shared_ptr<const Model> model;
  };
  LoadOptions options_;
  mutable std::mutex mutex_;
  std::map<std::string, Entry> entries_;
  size_t loads_ = 0;
};

}  // namespace welkin::assets
