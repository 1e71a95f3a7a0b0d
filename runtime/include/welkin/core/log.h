#pragma once
// Minimal leveled logging to stderr; stdout is kept for command output (--json must stay parseable).
#include <string_view>

namespace welkin::log {

enum class Level { debug, info, warn, error, quiet };
void set_level(Level level);
Level level();
void write(Level level, std::string_view text);

inline void debug(std::string_view t) { write(Level::debug, t); }
inline void info(std::string_view t) { write(Level::info, t); }
inline void warn(std::string_view t) { write(Level::warn, t); }

}  // namespace welkin::log
