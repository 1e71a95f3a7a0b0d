#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace welkin::cli {
// Each adds its subcommand to the app; the callback stores the exit code in `exit_code`.
void add_render_command(CLI::App& app, int& exit_code);
void add_info_command(CLI::App& app, int& exit_code);
void add_sun_command(CLI::App& app, int& exit_code);
void add_sequence_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_probe_command(CLI::App& app, int& exit_code);
void add_accuracy_command(CLI::App& app, int& exit_code);
// `welkin accuracy clouds`: the GPU march against the path-traced reference per quality preset and
// multiple-scattering model, with GPU time; writes a CSV and a plot into `out`.
struct CloudAccuracyOptions {
  std::string out = "out/accuracy", size = "640x360";
  std::string ghosting_scene = "assets/scenes/clouds-peer.json";  // the temporal upscaling's flight
  std::vector<std::string> qualities{"low", "medium", "high", "ultra"};
  int frames = 5;
  bool quick = false, json = false;
};
int run_cloud_accuracy(const CloudAccuracyOptions& options);
// Prints nodes, meshes, counts, materials, extensions and bounds of a glTF; throws welkin::Error.
void print_asset_info(const std::string& file, bool json);
// Parses WIDTHxHEIGHT (1..kMaxImageSide per side, at most kMaxImagePixels); throws Error naming --size.
void parse_size(const std::string& text, int& width, int& height);
}  // namespace welkin::cli
