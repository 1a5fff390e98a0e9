// Resolved-rate Cartesian teleop for the UR5, checked against the forward kinematics it inverts:
// one control tick of its output moves the tool point as asked and leaves the tool's orientation
// alone, around the simulated arm's home and with the base moved and turned on the table.

#include "engine/teach/resolved_rate.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/core/rng.h"
#include "engine/safety/ur5_kinematics.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::teach {
namespace {

using Joints = std::array<double, 6>;
constexpr double kDt_s = 0.01;

/// The simulated arm's home with every joint moved by up to +-0.3 rad.
Joints NearHome(Rng& rng) {
  Joints q = worlds::Ur5Arm::kHome;
  for (double& x : q) x += rng.Uniform(-0.3, 0.3);
  return q;
}

Eigen::Vector3d RandomDirection(Rng& rng) {
  const Eigen::Vector3d v(rng.Normal(), rng.Normal(), rng.Normal());
  return v.normalized();
}

Joints Integrate(const Joints& q, const Joints& qd, double dt_s) {
  Joints next = q;
  for (int i = 0; i < 6; ++i) next[i] += qd[i] * dt_s;
  return next;
}

/// Where the tool point is in the table frame.
Eigen::Vector3d ToolInTable(const Joints& q, const Eigen::Isometry3d& base_in_table) {
  return base_in_table * safety::Ur5ToolPoint(q, 0.1);
}

/// The angle between the flange's orientations at q0 and q1, radians.
double TurnRad(const Joints& q0, const Joints& q1) {
  const Eigen::Matrix3d r0 = safety::Ur5FlangePose(q0).linear();
  const Eigen::Matrix3d r1 = safety::Ur5FlangePose(q1).linear();
  return Eigen::AngleAxisd(r1 * r0.transpose()).angle();
}

double Fastest(const Joints& qd) {
  double fastest = 0;
  for (double x : qd) fastest = std::max(fastest, std::abs(x));
  return fastest;
}

TEST(CartesianVelocityTest, TheJacobianMatchesTheForwardKinematics) {
  Rng rng(3);  // seed 3: 10 poses and joint directions
  for (int trial = 0; trial < 10; ++trial) {
    const Joints q = NearHome(rng);
    Joints qd;
    for (double& x : qd) x = rng.Uniform(-1, 1);
    const Eigen::Matrix<double, 6, 6> jacobian = Ur5ToolJacobian(q, 0.1);
    Eigen::Matrix<double, 6, 1> qd_vector;
    for (int i = 0; i < 6; ++i) qd_vector(i) = qd[i];
    const Eigen::Matrix<double, 6, 1> twist = jacobian * qd_vector;
    // A tiny finite step of the real kinematics against the Jacobian's prediction.
    const double h = 1e-6;
    const Joints q1 = Integrate(q, qd, h);
    const Eigen::Vector3d moved = (safety::Ur5ToolPoint(q1, 0.1) - safety::Ur5ToolPoint(q, 0.1));
    EXPECT_LT((moved / h - twist.head<3>()).norm(), 1e-4) << "trial " << trial;
    const Eigen::AngleAxisd turn(safety::Ur5FlangePose(q1).linear() *
                                 safety::Ur5FlangePose(q).linear().transpose());
    EXPECT_LT((turn.angle() * turn.axis() / h - twist.tail<3>()).norm(), 1e-4) << "trial " << trial;
  }
}

TEST(CartesianVelocityTest, OneTickMovesTheToolAsAskedAndKeepsItsOrientation) {
  Rng rng(11);  // seed 11: 20 poses, base placements and velocities
  for (int trial = 0; trial < 20; ++trial) {
    const Joints q = NearHome(rng);
    // Every other trial the base is moved and turned on the table, as a real cell may have it.
    Eigen::Isometry3d base_in_table = Eigen::Isometry3d::Identity();
    if (trial % 2 == 1) {
      base_in_table.translate(Eigen::Vector3d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), 0.02));
      base_in_table.rotate(Eigen::AngleAxisd(rng.Uniform(-M_PI, M_PI), Eigen::Vector3d::UnitZ()));
    }
    // 2-8 cm/s, as a teacher drives the gripper; slow enough that the speed cap stays out.
    const Eigen::Vector3d v_m_s = rng.Uniform(0.02, 0.08) * RandomDirection(rng);
    const Joints qd = CartesianJointVelocities(q, v_m_s, base_in_table);
    ASSERT_LT(Fastest(qd), 0.6) << "trial " << trial << ": the cap changed the motion";
    const Joints q1 = Integrate(q, qd, kDt_s);
    const Eigen::Vector3d moved = ToolInTable(q1, base_in_table) - ToolInTable(q, base_in_table);
    const Eigen::Vector3d wanted = v_m_s * kDt_s;
    EXPECT_LT((moved - wanted).norm(), 0.03 * wanted.norm())
        << "trial " << trial << ": moved " << moved.transpose() << ", wanted "
        << wanted.transpose();
    EXPECT_LT(TurnRad(q, q1), 1e-3) << "trial " << trial;
  }
}

TEST(CartesianVelocityTest, ZeroOrNonFiniteVelocityGivesExactlyZero) {
  const Joints q = worlds::Ur5Arm::kHome;
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  EXPECT_EQ(CartesianJointVelocities(q, Eigen::Vector3d::Zero(), identity), Joints{});
  EXPECT_EQ(CartesianJointVelocities(q, Eigen::Vector3d(NAN, 0, 0), identity), Joints{});
  Joints bad_q = q;
  bad_q[2] = INFINITY;
  EXPECT_EQ(CartesianJointVelocities(bad_q, Eigen::Vector3d(0.05, 0, 0), identity), Joints{});
  // And a non-zero velocity does move (so the checks above are not vacuous).
  EXPECT_GT(Fastest(CartesianJointVelocities(q, Eigen::Vector3d(0.05, 0, 0), identity)), 1e-3);
}

TEST(CartesianVelocityTest, TheSpeedCapScalesTheWholeMotionAndKeepsItsDirection) {
  Rng rng(5);  // seed 5: 10 poses and directions
  CartesianVelocityOptions options;
  options.max_joint_speed_rad_s = 0.4;
  for (int trial = 0; trial < 10; ++trial) {
    const Joints q = NearHome(rng);
    const Eigen::Vector3d v_m_s = 1.0 * RandomDirection(rng);  // far faster than 0.4 rad/s allows
    const Joints qd = CartesianJointVelocities(q, v_m_s, Eigen::Isometry3d::Identity(), options);
    EXPECT_NEAR(Fastest(qd), 0.4, 1e-12) << "trial " << trial;
    const Joints q1 = Integrate(q, qd, kDt_s);
    const Eigen::Vector3d moved = safety::Ur5ToolPoint(q1, 0.1) - safety::Ur5ToolPoint(q, 0.1);
    EXPECT_GT(moved.normalized().dot(v_m_s.normalized()), 0.999) << "trial " << trial;
    EXPECT_LT(moved.norm(), v_m_s.norm() * kDt_s) << "trial " << trial;
    EXPECT_LT(TurnRad(q, q1), 1e-3) << "trial " << trial;
  }
}

TEST(CartesianVelocityTest, AtAWristSingularityTheResultIsFiniteAndCapped) {
  // Wrist 2 at 0 lines wrist 1 and wrist 3 up: the Jacobian loses rank.
  Joints q = worlds::Ur5Arm::kHome;
  q[4] = 0.0;
  const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(Ur5ToolJacobian(q, 0.1));
  ASSERT_LT(svd.singularValues()(5), 1e-6) << "not singular: the test would prove nothing";
  CartesianVelocityOptions undamped;
  undamped.damping = 0.0;
  for (const Eigen::Vector3d& v :
       {Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(0, 0.05, 0), Eigen::Vector3d(0, 0, -0.05)}) {
    for (const CartesianVelocityOptions& options : {CartesianVelocityOptions{}, undamped}) {
      const Joints qd = CartesianJointVelocities(q, v, Eigen::Isometry3d::Identity(), options);
      for (double x : qd) EXPECT_TRUE(std::isfinite(x));
      EXPECT_LE(Fastest(qd), options.max_joint_speed_rad_s + 1e-12);
    }
  }
  // Just off the singularity, damping keeps the joints from racing (an undamped inverse would
  // need huge wrist speeds for the lost direction).
  q[4] = 1e-4;
  const Joints damped =
      CartesianJointVelocities(q, Eigen::Vector3d(0, 0.05, 0), Eigen::Isometry3d::Identity());
  for (double x : damped) EXPECT_TRUE(std::isfinite(x));
  EXPECT_LE(Fastest(damped), 0.6 + 1e-12);
}

TEST(CartesianVelocityTest, NonsenseOptionsAreRefused) {
  CartesianVelocityOptions options;
  options.max_joint_speed_rad_s = 0;
  EXPECT_THROW(CartesianJointVelocities(worlds::Ur5Arm::kHome, Eigen::Vector3d(0.1, 0, 0),
                                        Eigen::Isometry3d::Identity(), options),
               std::invalid_argument);
}

}  // namespace
}  // namespace recon::teach
