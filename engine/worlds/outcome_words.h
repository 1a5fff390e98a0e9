#pragma once

#include <map>
#include <string>

namespace recon::worlds {

/// Why a test scene failed, in a teacher's words, from the world's outcome details
/// (World::OutcomeDetails): "never picked the toast up", "closed the gripper on nothing", "kept
/// holding the toast to the end", "dropped the toast off the table", "delivered towards the
/// bowl", "let the toast go off the plate, 14 cm from its middle".
/// "" for a scene that succeeded, and for worlds whose details say nothing of a grasp (the 2-D
/// worlds): their metric already says how far off they were.
std::string DescribeFailure(const std::map<std::string, double>& details, bool succeeded);

}  // namespace recon::worlds
