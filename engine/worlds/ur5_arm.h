#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/physical_bounds.h"

namespace recon::worlds {

/// Joint-space vector of the UR5's six joints, base to wrist, radians (or rad/s).
using Ur5Joints = std::array<double, 6>;

/// The UR5 of assets/mjcf/ur5.xml inside a scene: its state, its velocity interface, its gripper
/// and an inverse-kinematics solver. Worlds and the simulated arm device both drive it.
///
/// Velocity control follows UR's speedj: each command is a joint velocity, clamped to the UR5's
/// pi rad/s, that is integrated into the set-point of a stiff position servo, with gravity
/// compensated the way the real controller does; so a zero command holds the arm still instead of
/// letting it sag.
///
/// Holding objects: a weld, not friction. Each graspable object has a disabled
/// `<weld name="grasp_<body>" body1="ur5_gripper" body2="<body>"/>` in the scene; closing the
/// gripper with the object between the finger tips switches that weld on at the current relative
/// pose, opening switches it off. Why: contact grasps of small objects with a velocity-servoed arm
/// slip or jitter depending on solver settings, which would make demonstrations and experiments
/// depend on contact tuning rather than on what is being taught. The fingers still close (to the
/// object's width) so the images show a grasp.
class Ur5Arm {
 public:
  static constexpr int kJoints = 6;
  static constexpr double kMaxJointSpeed_rad_s = kUr5MaxJointSpeed_rad_s;
  /// A pose above the table with the tool pointing down: the arm's home and the IK's default seed.
  static constexpr Ur5Joints kHome = {3.14159265358979, -1.9, 1.9, -1.5708, -1.5708, 0.0};

  /// Finds the arm in `scene` (which must outlive this object). UserError if the scene lacks any
  /// of the arm's joints, actuators or sites.
  explicit Ur5Arm(MujocoModel& scene);

  /// Puts the arm at `q` at rest, gripper open, nothing held, and recomputes positions.
  void Reset(const Ur5Joints& q);
  /// Poses the arm without simulating it, as Reset does, with the fingers at `gripper_opening`
  /// (0 closed, 1 open, clamped): what a digital twin shows of an arm whose joints come from
  /// elsewhere. Nothing is held.
  void ShowPose(const Ur5Joints& q, double gripper_opening);

  Ur5Joints JointPositions() const;
  Ur5Joints JointVelocities() const;
  /// Finger opening, 0 (closed) to 1 (fully open).
  double GripperOpening() const;
  /// Position of the point between the finger tips, world frame, metres.
  Eigen::Vector3d GripPosition() const;
  /// The body id of the object held, or -1.
  int HeldObject() const { return held_object_; }
  /// Names of the bodies the gripper can hold (those with a grasp_<body> weld).
  std::vector<std::string> GraspableObjects() const;
  /// The highest the grip point (world z) may be, tool pointing down, for closing the gripper
  /// over body `object` where it lies now to hold it: the finger pads must reach down its side.
  /// Nullopt for a body the scene does not have. What a teacher's height readout marks.
  std::optional<double> HighestGraspHeight(const std::string& object) const;

  /// Where an object lies relative to the open fingers: what decides whether closing holds it.
  struct GraspAlignment {
    Eigen::Vector3d closing_axis;  ///< the fingers' closing direction, world frame (unit)
    double along_closing_m = 0;    ///< the object's centre off the grip point along it
    double along_faces_m = 0;      ///< ... and along the finger faces
    /// How far each may be for a close to hold the object (GraspOffset's window).
    double closing_window_m = 0, faces_window_m = 0;
  };
  /// Nullopt for a body the scene does not have. For a teacher's readout ("the toast is 2 cm
  /// off the jaw's axis") and the jaw's axis drawn in the teacher's view.
  std::optional<GraspAlignment> AlignmentWith(const std::string& object) const;

  /// Sets the joint velocity command (rad/s); each entry is clamped to kMaxJointSpeed_rad_s.
  /// Non-finite entries are treated as 0 (a safety stop, not an exception, inside a rollout).
  void CommandJointVelocities(const Ur5Joints& qd);
  /// Closes (grasping whatever is between the fingers) or opens (releasing) the gripper.
  void CommandGripper(bool close);
  bool GripperClosed() const { return gripper_closed_; }
  /// The fingers are still on their way in (the first 0.6 s after a close): an object that comes
  /// between them meanwhile is caught.
  bool FingersClosing() const { return closing_left_s_ > 0; }

  /// Advances the whole scene by `duration_s` of simulated time under the current commands.
  void Step(double duration_s);

  /// Joint angles that put the grip point at `target` (world frame) with the tool pointing
  /// straight down and the fingers' closing axis at `yaw_rad` about the vertical; nullopt if no
  /// solution within 1 mm is found from `seed` (an unreachable layout).
  std::optional<Ur5Joints> SolveGraspIk(const Eigen::Vector3d& target, double yaw_rad,
                                        const Ur5Joints& seed) const;

 private:
  void UpdateGrasp();
  int FindGraspable() const;
  /// The distance from the grip point to `object`'s centre if closing the fingers now would hold
  /// it (a real parallel gripper's window, see ur5_arm.cc), nullopt otherwise.
  std::optional<double> GraspOffset(int object) const;

  struct ScratchDeleter {
    void operator()(mjData_* d) const;
  };

  MujocoModel* scene_;
  // IK works on its own copy of the state; making an mjData costs far more than an IK solve.
  std::unique_ptr<mjData_, ScratchDeleter> ik_data_;
  std::array<int, kJoints> qpos_adr_{}, dof_adr_{}, actuator_{};
  std::array<int, 2> finger_qpos_adr_{}, finger_actuator_{};
  int grip_site_ = -1, gripper_body_ = -1;
  std::vector<int> grasp_welds_;  // equality ids
  Ur5Joints command_{}, setpoint_{};
  bool gripper_closed_ = false;
  double closing_left_s_ = 0.0;  ///< the fingers are still closing this much longer
  int held_object_ = -1;
  double finger_closed_target_ = 0.0;
  double finger_setpoint_ = 0.06;  ///< where the fingers are being driven, moving at their speed
};

}  // namespace recon::worlds
