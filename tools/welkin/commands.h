#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "run_folder.h"

namespace welkin::cli {
// Each adds its subcommand to the app; the callback stores the exit code in `exit_code`.
void add_render_command(CLI::App& app, int& exit_code);
void add_info_command(CLI::App& app, int& exit_code);
void add_sun_command(CLI::App& app, int& exit_code);
void add_sequence_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_probe_command(CLI::App& app, int& exit_code);
void add_accuracy_command(CLI::App& app, int& exit_code);
// `welkin farm slurm` (batch scripts for a Slurm cluster) and `welkin farm status` (a frames folder's progress).
void add_farm_command(CLI::App& app, int& exit_code);
// `welkin metar`: decodes a METAR report (and the sky the weather module makes of it).
void add_metar_command(CLI::App& app, int& exit_code);
// The options that decide a sequence run's frames (--fps, --size, --from, --to, --exr), shared by
// `welkin sequence` and `welkin farm slurm` so both take them alike.
void add_run_options(CLI::App& cmd, RunSettings& run);
// --video and --contact-sheet: made from a whole run's frames.
void add_assembly_options(CLI::App& cmd, std::string& video, std::string& contact_sheet);
// Checks them against the run before any frame is rendered; throws Error naming the option.
void check_assembly_options(const RunManifest& run, const std::string& video, const std::string& contact_sheet);
// `welkin accuracy clouds`: the GPU march against the path-traced reference per quality preset and
// multiple-scattering model, with GPU time; writes a CSV and a plot into `out`.
struct CloudAccuracyOptions {
  std::string out = "out/accuracy", size = "640x360";
  std::string ghosting_scene = "assets/scenes/clouds-peer.json";  // the temporal upscaling's flight
  std::string scene;  // the layers and sun measured ("": the built-in cumulus case)
  std::string rays;   // the view rays measured ("": the built-in set)
  std::string image;  // a scene: path-traced image panels instead of the sweep
  std::string cache;  // the path-traced rays kept between runs ("": DiskCache::from_environment's folder)
  int paths_per_pixel = 64;
  bool fit = false;  // fit the light model's weights instead of the sweep
  std::vector<std::string> fit_also;  // --fit: further training sets, each "SCENE,RAYS"
  std::vector<std::string> fit_kept_back;  // --fit: sets marched and reported but not fitted, each "SCENE,RAYS"
  std::vector<int> fit_terms;  // --fit: the candidate terms solved for (empty: all)
  bool light_only = false;  // the rays' errors and the term budget only: no GPU time, ghosting or aerial perspective
  bool silhouettes_only = false;  // the temporal upscaling's silhouettes in the ghosting scene only
  std::vector<std::string> qualities{"low", "medium", "high", "ultra"};
  int frames = 5;
  bool quick = false, json = false;
};
int run_cloud_accuracy(const CloudAccuracyOptions& options);
// `welkin accuracy godrays`: each method and setting against a reference march of the same scene's
// frame, with the shafts' GPU time; writes a CSV, a plot and images of the shafts into `out`.
struct GodRayAccuracyOptions {
  std::string out = "out/accuracy", size = "320x180";
  std::string scene = "assets/scenes/godrays-sunset.json";
  int frames = 5;
  bool quick = false, json = false;
};
int run_god_ray_accuracy(const GodRayAccuracyOptions& options);
// `welkin accuracy clusters`: the mesh clusters' light quadrature against 16 samples with their GPU
// time, and their consistency with the volumetric path at the switch distance; writes a CSV.
struct ClusterAccuracyOptions {
  std::string out = "out/accuracy", size = "320x180";
  std::string scene = "assets/scenes/clouds-clusters.json";
  int frames = 5;
  bool quick = false;  // the consistency at the switch alone (no quadrature sweep)
  bool json = false;
};
int run_cluster_accuracy(const ClusterAccuracyOptions& options);
// `welkin accuracy billboards`: the impostor against its reference (the same archetypes marched) for
// several atlas sizes and view grids, with GPU times, and the consistency with the volumetric path
// at the switch distance; writes a CSV.
struct BillboardAccuracyOptions {
  std::string out = "out/accuracy", size = "320x180";
  std::string scene = "assets/scenes/clouds-billboards.json";
  int frames = 5;
  bool quick = false, json = false;
};
int run_billboard_accuracy(const BillboardAccuracyOptions& options);
// Prints nodes, meshes, counts, materials, extensions and bounds of a glTF; throws welkin::Error.
void print_asset_info(const std::string& file, bool json);
// Parses WIDTHxHEIGHT (1..kMaxImageSide per side, at most kMaxImagePixels); throws Error naming --size.
void parse_size(const std::string& text, int& width, int& height);
}  // namespace welkin::cli
