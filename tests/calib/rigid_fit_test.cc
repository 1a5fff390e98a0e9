#include "engine/calib/rigid_fit.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::calib {
namespace {

using ::testing::HasSubstr;

std::vector<Eigen::Vector3d> RandomPoints(Rng& rng, int n, bool planar) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    points.emplace_back(rng.Uniform(-1, 1), rng.Uniform(-0.6, 0.6),
                        planar ? 0.02 : rng.Uniform(0, 0.5));
  }
  return points;
}

TEST(RigidFitTest, Recovers2DTransformExactly) {
  Rng rng(1);
  const auto from = RandomPoints(rng, 8, true);
  RigidTransform truth;
  truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  truth.translation = {0.35, -1.2, 0.04};
  std::vector<Eigen::Vector3d> to;
  for (const auto& p : from) to.push_back(truth.Apply(p));
  const RigidTransform fit = FitRigid(from, to, FitDimension::k2D);
  EXPECT_NEAR(fit.YawRad(), 0.7, 1e-12);
  EXPECT_LT((fit.translation - truth.translation).norm(), 1e-12);
  EXPECT_NEAR(fit.rotation.determinant(), 1.0, 1e-12);
}

TEST(RigidFitTest, Recovers3DTransformExactly) {
  Rng rng(2);
  const auto from = RandomPoints(rng, 10, false);
  RigidTransform truth;
  truth.rotation = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
                    Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()))
                       .toRotationMatrix();
  truth.translation = {-0.5, 0.25, 0.8};
  std::vector<Eigen::Vector3d> to;
  for (const auto& p : from) to.push_back(truth.Apply(p));
  const RigidTransform fit = FitRigid(from, to, FitDimension::k3D);
  EXPECT_LT((fit.rotation - truth.rotation).norm(), 1e-10);
  EXPECT_LT((fit.translation - truth.translation).norm(), 1e-10);
}

TEST(RigidFitTest, MirroredPointsStillGiveAProperRotation) {
  // Targets that are a mirror image of the sources: the best proper rotation is not the mirror.
  std::vector<Eigen::Vector3d> from = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {1, 2, 0}};
  std::vector<Eigen::Vector3d> to;
  for (const auto& p : from) to.emplace_back(-p.x(), p.y(), p.z());
  const RigidTransform fit = FitRigid(from, to, FitDimension::k2D);
  EXPECT_NEAR(fit.rotation.determinant(), 1.0, 1e-12);
}

TEST(RigidFitTest, BadInputIsAUserError) {
  const std::vector<Eigen::Vector3d> one = {{0, 0, 0}};
  try {
    FitRigid(one, one, FitDimension::k2D);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("at least 2 points"));
  }
  const std::vector<Eigen::Vector3d> same = {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}};
  EXPECT_THROW(FitRigid(same, same, FitDimension::k2D), UserError);
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  try {
    FitRigid(line, line, FitDimension::k3D);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("one line"));
  }
  std::vector<Eigen::Vector3d> with_nan = line;
  with_nan[2].y() = NAN;
  try {
    FitRigid(with_nan, line, FitDimension::k2D);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("point 2"));
    EXPECT_THAT(e.what(), HasSubstr("UWB"));
  }
  EXPECT_THROW(FitRigid(line, one, FitDimension::k2D), UserError);
}

}  // namespace
}  // namespace recon::calib
