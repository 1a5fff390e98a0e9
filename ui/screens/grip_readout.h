#pragma once

#include <string>

#include "ui/studio/studio_snapshot.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

/// What the Record screen says of the grip, as text: the state in words and colour (whether a
/// grasp worked is the first thing a teacher needs to know, and a closed gripper says nothing of
/// it), the height, and what to do next to grasp. A function of the snapshot alone, so that a test
/// can check it in every grip state.
struct GripReadout {
  Status status = Status::kOff;
  std::string state;   ///< "Holding the toast", "Closed on nothing: ...", ...
  std::string height;  ///< "Height 4.2 cm; it grasps the toast at 0.5-1.1 cm"
  std::string hint;    ///< "lower 1.2 cm more before closing", or ""
  /// The wrist's turn and how to turn it ("Wrist turned 12° (Home / End, up to 90° either
  /// way)"); at its limit a warning that names the key or stick that turns it back. Empty for
  /// the scripted teacher, which turns the wrist itself.
  Status wrist_status = Status::kOff;
  std::string wrist;
};

GripReadout ReadGrip(const StudioSnapshot& s);

}  // namespace recon::ui
