#include "engine/worlds/physical_bounds.h"

namespace recon::worlds {

namespace {

constexpr int kUr5Joints = 6;

void AddJoints(std::vector<ValueRange>& ranges, double limit, const char* quantity) {
  for (int j = 0; j < kUr5Joints; ++j) {
    ranges.push_back({-limit, limit, "joint " + std::to_string(j) + " " + quantity});
  }
}

std::vector<ValueRange> Positions(int64_t count, const char* what) {
  std::vector<ValueRange> ranges;
  for (int64_t i = 0; i < count; ++i) {
    ranges.push_back({-kCellRadius_m, kCellRadius_m, std::string(what) + " (m)"});
  }
  return ranges;
}

}  // namespace

ValueBounds PhysicalBounds(const std::string& world, const DataSpec& spec) {
  const bool tabletop = world == "tabletop" || world == "tabletop-state";
  if (!tabletop && world != "bintransfer") return {};
  // The tabletop's x and u end in the gripper: its opening (0 shut, 1 open) and its command.
  const int gripper = tabletop ? 1 : 0;
  if (spec.x_dim != kUr5Joints + gripper || spec.u_dim != kUr5Joints + gripper) return {};
  ValueBounds bounds;
  AddJoints(bounds.x, kUr5JointLimit_rad, "angle (rad)");
  // A command at the clamp, stored as a float, may round a little above it.
  AddJoints(bounds.u, kUr5MaxJointSpeed_rad_s + 1e-3, "velocity command (rad/s)");
  if (tabletop) {
    bounds.x.push_back({0.0, 1.0, "gripper opening (0 shut, 1 open)"});
    bounds.u.push_back({0.0, 1.0, "gripper command (0 open, 1 close)"});
  }
  // A vector y holds object positions; b beacon positions or distances, all in metres.
  if (!spec.YIsImage()) bounds.y = Positions(spec.YSize(), "object coordinate");
  bounds.b = Positions(spec.b_dim, "beacon reading");
  return bounds;
}

}  // namespace recon::worlds
