// `welkin`: the command-line front end of the engine. Subcommands render, info, ...
#include <cstdio>

#include "commands.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/core/log.h"

int main(int argc, char** argv) {
  CLI::App app{"Welkin: physically based skies. Renders scenes, inspects modules and measures techniques."};
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log module loading and other progress details");
  int exit_code = welkin::cli::kOk;
  welkin::cli::add_render_command(app, exit_code);
  welkin::cli::add_info_command(app, exit_code);
  welkin::cli::add_sun_command(app, exit_code);
  welkin::cli::add_sequence_command(app, exit_code);
  welkin::cli::add_bench_command(app, exit_code);
  welkin::cli::add_probe_command(app, exit_code);
  welkin::cli::add_accuracy_command(app, exit_code);
  welkin::cli::add_farm_command(app, exit_code);
  welkin::cli::add_metar_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return welkin::cli::kUsage;
  } catch (const welkin::Error& e) {
    std::fprintf(stderr, "welkin: error: %s\n", e.what());
    return welkin::cli::kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "welkin: error: %s\n", e.what());
    return welkin::cli::kFailure;
  }
  return exit_code;
}
