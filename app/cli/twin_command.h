#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon twin up DIR [--seed S] [--seconds T]` and `recon twin move DIR [--plate X,Y]
/// [--bowl X,Y] [--toast X,Y]`: a digital twin of a real cell to try the real path without
/// hardware. `up` runs a fake UR controller on loopback and the plate's beacon, a fake DWM1001 on
/// a pseudo-terminal that reports where DIR/layout.json puts the plate through a hidden UWB
/// frame, writes DIR/cell.json for `recon-studio --cell`, and runs until Ctrl-C (or T seconds);
/// `move` rewrites the layout, as a person moves the objects.
void AddTwinCommand(CLI::App& app);

}  // namespace recon::cli
