#include "devices/robot/ur5_kinematics.h"

#include <Eigen/Geometry>

#include "engine/safety/ur5_kinematics.h"

namespace recon::robot {

std::array<double, 6> Ur5TcpPose(const std::array<double, 6>& q_rad) {
  // The same DH model the safety envelope judges the tool height with.
  const Eigen::Isometry3d pose = safety::Ur5FlangePose(q_rad);
  const Eigen::AngleAxisd rotation(pose.rotation());
  const Eigen::Vector3d r = rotation.axis() * rotation.angle();
  const Eigen::Vector3d p = pose.translation();
  return {p.x(), p.y(), p.z(), r.x(), r.y(), r.z()};
}

}  // namespace recon::robot
