// recon: the command-line face of RECON Studio. Wiring only; the work is in engine/.

#include <CLI/CLI.hpp>

#include "app/cli/recon_app.h"
#include "app/cli/run_main.h"
#include "engine/core/malloc_tuning.h"

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  CLI::App app{"recon: teach a robot with human-placed beacons (RECON)"};
  recon::cli::GlobalOptions global;
  recon::cli::BuildReconApp(app, global);
  return recon::cli::RunMain(app, argc, argv, "recon");
}
