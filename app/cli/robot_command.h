#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon robot status --host H [--rtde-port 30004] [--script-port 30002] [--seconds 1]
/// [--json] [--fake]`: connects to a UR controller over RTDE and reports its version, robot and
/// safety modes, joints and the measured data rate. --fake runs against a built-in fake
/// controller on loopback, for trying the studio without a robot.
void AddRobotCommand(CLI::App& app);

}  // namespace recon::cli
