#pragma once
// What every `welkin` subcommand shares: a world whose modules come from the plugin folder,
// scene loading with `--set` overrides, and the error/exit-code convention.
#include <memory>
#include <string>
#include <vector>

#include "welkin/core/world.h"
#include "welkin/gfx/image.h"

namespace welkin {
class Renderer;
}

namespace welkin::cli {

enum ExitCode { kOk = 0, kFailure = 1, kUsage = 2, kBadInput = 3 };

// Folders searched for plugin modules (WELKIN_MODULE_PATH first, then beside the executable).
std::vector<std::string> module_search_dirs();
std::unique_ptr<World> make_world();
// Applies "component/field/path=value" (value parsed as JSON, else taken as a string) to the first
// entity that has the component; throws Error naming the assignment.
void apply_assignment(World& world, const std::string& assignment);

// For the accuracy commands: one frame rendered alone (the clouds march every pixel: no history)
// at a fixed index (the noise), read back in full precision.
ImageF render_still(Renderer& renderer, int width, int height);
// The median GPU milliseconds of the passes whose names start with `prefix`, over `frames` frames
// after two warm-up frames, and of a full-screen copy measured between them.
std::pair<double, double> passes_cost(Renderer& renderer, const std::string& prefix, int width, int height, int frames);

}  // namespace welkin::cli
