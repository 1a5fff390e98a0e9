// recon: the command-line face of RECON Studio. Wiring only; the work is in engine/.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/cli/cell_commands.h"
#include "app/cli/experiment_command.h"
#include "app/cli/record_command.h"
#include "app/cli/report_command.h"
#include "app/cli/session_command.h"
#include "app/cli/train_commands.h"
#include "engine/core/error.h"
#include "engine/core/malloc_tuning.h"

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  CLI::App app{"recon: teach a robot with human-placed beacons (RECON)"};
  app.set_version_flag("--version", "recon 0.1.0");
  app.require_subcommand(1);
  recon::cli::GlobalOptions global;
  app.add_option("--threads", global.threads, "Torch threads per training job")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  recon::cli::AddExperimentCommands(app, global);
  recon::cli::AddCellCommands(app);
  recon::cli::AddRecordCommand(app);
  recon::cli::AddTrainCommands(app, global);
  recon::cli::AddSessionCommands(app);
  recon::cli::AddReportCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    // CLI11 uses 0 for --help/--version; every real parse error is a usage error (2).
    return code == 0 ? 0 : 2;
  } catch (const recon::UserError& e) {
    std::fprintf(stderr, "\nrecon: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\nrecon: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
