#pragma once

#include <array>
#include <optional>
#include <string>

namespace recon::teach {

/// How an arm is brought back to its home pose before a trial: a joint-space move, every joint
/// arriving together (the velocity scaled as a whole, keeping its direction), proportional to
/// what is left so that it slows down into the pose instead of overshooting it.
struct HomingLimits {
  /// The fastest joint during the move: a third of the envelope's 1 rad/s, so that a person
  /// beside the table sees it coming.
  double max_speed_rad_s = 0.3;
  /// Proportional gain (1/s): the speed is gain x the distance left, up to the cap. At 10 Hz a
  /// gain of 2 takes a fifth of what is left each period.
  double gain_per_s = 2.0;
  /// Every joint within this of home: the arm is home (0.005 rad moves the tool about 4 mm).
  double tolerance_rad = 0.005;
  /// A joint further than this from home is not driven there automatically (a wrapped wrist,
  /// an arm parked far away): the person brings it near with the pendant first.
  double max_distance_rad = 3.1416;

  /// UserError naming the field unless each is a positive finite number.
  void Validate() const;
};

/// The largest joint distance from `q_rad` to `home_rad` (rad); infinite for non-finite joints.
double HomingDistance(const std::array<double, 6>& q_rad, const std::array<double, 6>& home_rad);

/// What homing does next from `q_rad`: nothing when the arm is home (every joint within the
/// tolerance: stop it there), else the joint velocities for the next control period. UserError
/// when a joint is too far (max_distance_rad) or not a number, naming the joint.
std::optional<std::array<double, 6>> HomingVelocity(const std::array<double, 6>& q_rad,
                                                    const std::array<double, 6>& home_rad,
                                                    const HomingLimits& limits = {});

}  // namespace recon::teach
