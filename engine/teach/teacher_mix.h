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

}  // namespace recon::teach
