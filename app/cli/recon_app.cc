#include "app/cli/recon_app.h"

#include "app/cli/camera_command.h"
#include "app/cli/cell_commands.h"
#include "app/cli/devices_command.h"
#include "app/cli/option_checks.h"
#include "app/cli/record_command.h"
#include "app/cli/report_command.h"
#include "app/cli/robot_command.h"
#include "app/cli/session_command.h"
#include "app/cli/train_commands.h"
#include "app/cli/twin_command.h"
#include "app/cli/uwb_command.h"

namespace recon::cli {

void BuildReconApp(CLI::App& app, GlobalOptions& global) {
  app.set_version_flag("--version", "recon 0.1.0");
  app.require_subcommand(1);
  app.add_option("--threads", global.threads, "Torch threads per training job")
      ->capture_default_str()
      ->check(WholeBetween(1, ParallelismLimit()));
  AddExperimentCommands(app, global);
  AddCellCommands(app);
  AddRecordCommand(app);
  AddTrainCommands(app, global);
  AddSessionCommands(app);
  AddReportCommand(app);
  AddUwbCommand(app);
  AddCameraCommand(app);
  AddRobotCommand(app);
  AddTwinCommand(app);
  AddDevicesCommand(app);
}

}  // namespace recon::cli
