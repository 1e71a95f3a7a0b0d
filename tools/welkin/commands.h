#pragma once
#include <CLI/CLI.hpp>

namespace welkin::cli {
// Each adds its subcommand to the app; the callback stores the exit code in `exit_code`.
void add_render_command(CLI::App& app, int& exit_code);
void add_info_command(CLI::App& app, int& exit_code);
}  // namespace welkin::cli
