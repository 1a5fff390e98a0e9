// recon: the command-line face of RECON Studio. Wiring only; the work is in engine/.

#include <CLI/CLI.hpp>

#include "app/cli/camera_command.h"
#include "app/cli/cell_commands.h"
#include "app/cli/devices_command.h"
#include "app/cli/experiment_command.h"
#include "app/cli/option_checks.h"
#include "app/cli/record_command.h"
#include "app/cli/report_command.h"
#include "app/cli/robot_command.h"
#include "app/cli/run_main.h"
#include "app/cli/session_command.h"
#include "app/cli/train_commands.h"
#include "app/cli/uwb_command.h"
#include "engine/core/malloc_tuning.h"

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  CLI::App app{"recon: teach a robot with human-placed beacons (RECON)"};
  app.set_version_flag("--version", "recon 0.1.0");
  app.require_subcommand(1);
  recon::cli::GlobalOptions global;
  app.add_option("--threads", global.threads, "Torch threads per training job")
      ->capture_default_str()
      ->check(recon::cli::WholeBetween(1, recon::cli::ParallelismLimit()));
  recon::cli::AddExperimentCommands(app, global);
  recon::cli::AddCellCommands(app);
  recon::cli::AddRecordCommand(app);
  recon::cli::AddTrainCommands(app, global);
  recon::cli::AddSessionCommands(app);
  recon::cli::AddReportCommand(app);
  recon::cli::AddUwbCommand(app);
  recon::cli::AddCameraCommand(app);
  recon::cli::AddRobotCommand(app);
  recon::cli::AddDevicesCommand(app);
  return recon::cli::RunMain(app, argc, argv, "recon");
}
