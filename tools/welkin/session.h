#pragma once
// What every `welkin` subcommand shares: a world whose modules come from the plugin folder,
// scene loading with `--set` overrides, and the error/exit-code convention.
#include <memory>
#include <string>
#include <vector>

#include "welkin/core/world.h"

namespace welkin::cli {

enum ExitCode { kOk = 0, kFailure = 1, kUsage = 2, kBadInput = 3 };

// Folders searched for plugin modules (WELKIN_MODULE_PATH first, then beside the executable).
std::vector<std::string> module_search_dirs();
std::unique_ptr<World> make_world();
// Applies "component/field/path=value" (value parsed as JSON, else taken as a string) to the first
// entity that has the component; throws Error naming the assignment.
void apply_assignment(World& world, const std::string& assignment);

}  // namespace welkin::cli
