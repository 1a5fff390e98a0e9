#pragma once

// What a robot in each world can physically record (ValueBounds): the store refuses a sample
// outside these, naming it, so a hand-edited or damaged file cannot train a model on values no
// cell produced. The bounds are the hardware's, not the task's: a demonstration the teacher
// gave badly is still inside them.

#include <string>

#include "engine/core/dataset.h"
#include "engine/core/value_bounds.h"

namespace recon::worlds {

/// The UR5's joints turn +-360 degrees (UR5 datasheet), plus a little for a servo's overshoot.
constexpr double kUr5JointLimit_rad = 6.2832 + 0.01;
/// The UR5's joint speed limit (datasheet: 180 deg/s); speedj clamps commands to it.
constexpr double kUr5MaxJointSpeed_rad_s = 3.14159265358979;
/// No object in a UR5's cell is farther from its base than this; a DWM1001 ranges to about 60 m.
/// A reading in millimetres instead of metres (560 for 0.56 m) falls outside.
constexpr double kCellRadius_m = 100.0;

/// The bounds of a session of world `world` (a name of WorldNames, or another name for
/// imported data) with shapes `spec`. The UR5 worlds (tabletop, tabletop-state, bintransfer)
/// bound x, u, b and a vector y; the abstract 2-D worlds and imported data have none (their
/// units are not a machine's), so only finiteness is checked there. Empty too when `spec` does
/// not have the world's shapes: the shape check names that.
ValueBounds PhysicalBounds(const std::string& world, const DataSpec& spec);

}  // namespace recon::worlds
