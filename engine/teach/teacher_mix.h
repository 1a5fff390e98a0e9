#pragma once

#include <string>
#include <vector>

namespace recon::teach {

/// What to tell a teacher whose demonstrations come from more than one teleop (`sources`: each
/// demonstration's EpisodeMeta::source, e.g. "scripted-teleop", "keyboard-teleop"), or "" when
/// they come from one. Why: two styles for one scene (the scripted teacher moves in joint space
/// at 0.3 rad/s, a keyboard in straight lines at 0.1 m/s) give a policy two answers to average;
/// on the demo's studio session, four scripted takes and one keyboard take cost RECON (Play) 60
/// points of success (docs/studio.md).
std::string TeacherMixWarning(const std::vector<std::string>& sources);

/// Whether a demonstration from `source` was given by a person (the keyboard, a gamepad, a real
/// cell's teleop): everything but the scripted teacher. A person's pauses are left out of
/// training, and most takes by a person get the recipe for a person's takes.
bool IsAPersonsTake(const std::string& source);

/// Whether more than half of `person` (per demonstration: a person's take) are a person's.
bool MostlyAPersonsTakes(const std::vector<bool>& person);

}  // namespace recon::teach
