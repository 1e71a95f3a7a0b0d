#include "welkin/core/log.h"

#include <cstdio>

namespace welkin::log {
namespace {
Level g_level = Level::warn;
}

void set_level(Level l) { g_level = l; }
Level level() { return g_level; }

void write(Level l, std::string_view text) {
  if (l < g_level) return;
  static const char* names[] = {"debug", "info", "warning", "error", ""};
  std::fprintf(stderr, "welkin %s: %.*s\n", names[int(l)], int(text.size()), text.data());
}

}  // namespace welkin::log
