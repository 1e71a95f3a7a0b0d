#pragma once
// Points the disk cache (core/disk_cache.h) elsewhere for one test ("": no cache), then back.
#include <cstdlib>
#include <optional>
#include <string>

namespace welkin::testing {

class CacheFolder {
 public:
  explicit CacheFolder(const std::string& folder) {
    if (const char* v = std::getenv("WELKIN_CACHE_DIR")) saved_ = v;
    ::setenv("WELKIN_CACHE_DIR", folder.c_str(), 1);
  }
  ~CacheFolder() {
    if (saved_) ::setenv("WELKIN_CACHE_DIR", saved_->c_str(), 1);
    else ::unsetenv("WELKIN_CACHE_DIR");
  }
  CacheFolder(const CacheFolder&) = delete;
  CacheFolder& operator=(const CacheFolder&) = delete;

 private:
  std::optional<std::string> saved_;
};

}  // namespace welkin::testing
