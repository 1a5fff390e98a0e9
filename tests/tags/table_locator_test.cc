#include "devices/tags/table_locator.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <map>

#include "devices/tags/pinhole_camera.h"
#include "devices/tags/tag_detector.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "tests/tags/synthetic_scene.h"

namespace recon::tags {
namespace {

using testing::PlacedTag;
using testing::SceneCamera;
using testing::SceneOptions;

// A MuJoCo camera orientation looking roughly down: yaw about table z, then small tilts. With
// no yaw or tilt it is the identity (camera -z = table -z, image up = table +y).
Eigen::Matrix3d MujocoCameraOrientation(double yaw_rad, double tilt_x_rad, double tilt_y_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(tilt_x_rad, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(tilt_y_rad, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

PinholeCamera LocatorCamera(const SceneCamera& scene) {
  return PinholeCamera::FromMujoco(scene.fovy_deg, scene.width, scene.height, scene.position_m,
                                   scene.table_R_mujoco);
}

TEST(ApriltagTableLocatorTest, IntrinsicsFromFovyFollowMujoco) {
  const CameraIntrinsics a = CameraIntrinsics::FromFovy(90.0, 640, 480);
  EXPECT_NEAR(a.fy, 240.0, 1e-9);
  EXPECT_NEAR(a.fx, 240.0, 1e-9);
  EXPECT_DOUBLE_EQ(a.cx, 320.0);
  EXPECT_DOUBLE_EQ(a.cy, 240.0);
  const CameraIntrinsics b = CameraIntrinsics::FromFovy(60.0, 640, 480);
  EXPECT_NEAR(b.fy, 240.0 / std::tan(M_PI / 6.0), 1e-9);
  EXPECT_THROW(CameraIntrinsics::FromFovy(0.0, 640, 480), UserError);
  EXPECT_THROW(CameraIntrinsics::FromFovy(180.0, 640, 480), UserError);
  EXPECT_THROW(CameraIntrinsics::FromFovy(45.0, 0, 480), UserError);
}

TEST(ApriltagTableLocatorTest, MujocoOrientationBecomesOpenCvOrientation) {
  const Eigen::Matrix3d cv = PinholeCamera::CvFromMujocoRotation(Eigen::Matrix3d::Identity());
  EXPECT_TRUE(cv.isApprox(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix()));
  // A camera 1 m up looking down: the point below it is the image centre, table +x is to the
  // right and table +y is up (smaller rows).
  const PinholeCamera camera =
      PinholeCamera::FromMujoco(60.0, 640, 480, {0.0, 0.0, 1.0}, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(camera.Project({0.0, 0.0, 0.0}).isApprox(Eigen::Vector2d(320.0, 240.0)));
  EXPECT_GT(camera.Project({0.1, 0.0, 0.0}).x(), 320.0);
  EXPECT_LT(camera.Project({0.0, 0.1, 0.0}).y(), 240.0);
  EXPECT_THROW(PinholeCamera(camera.intrinsics(), {0, 0, 1}, 2.0 * Eigen::Matrix3d::Identity()),
               UserError);
  // A reflection is orthonormal but not a rotation.
  EXPECT_THROW(PinholeCamera(camera.intrinsics(), {0, 0, 1},
                             Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix()),
               UserError);
}

// PinholeCamera against the test scene's independent MuJoCo-style projection, for tilted and
// turned cameras (seed 51).
TEST(ApriltagTableLocatorTest, ProjectionAndRayAgreeWithTheMujocoFormulation) {
  Rng rng(51);
  for (int trial = 0; trial < 50; ++trial) {
    SceneCamera scene;
    scene.fovy_deg = rng.Uniform(30.0, 80.0);
    scene.position_m = {rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5), rng.Uniform(0.6, 1.5)};
    scene.table_R_mujoco = MujocoCameraOrientation(rng.Uniform(-M_PI, M_PI), rng.Uniform(-0.3, 0.3),
                                                   rng.Uniform(-0.3, 0.3));
    const PinholeCamera camera = LocatorCamera(scene);
    const Eigen::Vector3d point(rng.Uniform(-0.3, 0.3) + scene.position_m.x(),
                                rng.Uniform(-0.3, 0.3) + scene.position_m.y(),
                                rng.Uniform(0.0, 0.1));
    const Eigen::Vector2d pixel = testing::ProjectPoint(scene, point);
    EXPECT_LT((camera.Project(point) - pixel).norm(), 1e-9) << "trial " << trial;
    EXPECT_LT((camera.IntersectHorizontalPlane(pixel, point.z()) - point).norm(), 1e-9)
        << "trial " << trial;
  }
}

TEST(ApriltagTableLocatorTest, RayPlaneRefusesPlanesItCannotReach) {
  const PinholeCamera down =
      PinholeCamera::FromMujoco(60.0, 640, 480, {0.0, 0.0, 1.0}, Eigen::Matrix3d::Identity());
  EXPECT_THROW(down.IntersectHorizontalPlane({320.0, 240.0}, 1.5), UserError);  // above it
  // A camera looking horizontally (its -z along table +x) sees the horizon row parallel.
  const Eigen::Matrix3d sideways = MujocoCameraOrientation(0.0, 0.0, -M_PI / 2.0);
  const PinholeCamera level = PinholeCamera::FromMujoco(60.0, 640, 480, {0.0, 0.0, 1.0}, sideways);
  EXPECT_THROW(level.IntersectHorizontalPlane({320.0, 240.0}, 0.0), UserError);
  EXPECT_THROW(TableLocator(down, TagSpec{0.0, 0.0}), UserError);
  TableLocator locator(down, TagSpec{});
  EXPECT_THROW(locator.SetTagSpec(3, TagSpec{-0.05, 0.0}), UserError);
}

// The simulated cell: a 1.0 x 0.8 m table with a corner tag (6 cm, on the table top) near each
// corner and beacons (5 cm tags, 4.5 cm above the table) scattered between them, seen by a
// camera 1.0 m up, slightly tilted and turned like a hand-mounted one.
struct Cell {
  SceneCamera camera;
  std::vector<PlacedTag> tags;
};

constexpr double kBeaconHeightM = 0.045;

Cell MakeCell(uint64_t seed) {
  Rng rng(seed);
  Cell cell;
  cell.camera.position_m = {0.5 + rng.Uniform(-0.03, 0.03), 0.4 + rng.Uniform(-0.03, 0.03), 1.0};
  cell.camera.table_R_mujoco = MujocoCameraOrientation(
      rng.Uniform(-0.1, 0.1), rng.Uniform(-0.05, 0.05), rng.Uniform(-0.05, 0.05));
  const double corners[4][2] = {{0.06, 0.06}, {0.94, 0.06}, {0.94, 0.74}, {0.06, 0.74}};
  for (int i = 0; i < 4; ++i) {
    cell.tags.push_back({i, {corners[i][0], corners[i][1], 0.0}, rng.Uniform(-0.2, 0.2), 0.06});
  }
  while (cell.tags.size() < 9) {
    const Eigen::Vector3d center(rng.Uniform(0.15, 0.85), rng.Uniform(0.15, 0.65), kBeaconHeightM);
    bool clear = true;
    for (const PlacedTag& other : cell.tags) {
      clear = clear && (other.center_m.head<2>() - center.head<2>()).norm() > 0.12;
    }
    if (clear) {
      cell.tags.push_back(
          {static_cast<int>(100 + cell.tags.size()), center, rng.Uniform(-M_PI, M_PI), 0.05});
    }
  }
  return cell;
}

TableLocator CellLocator(const Cell& cell, LocateMethod method = LocateMethod::kRayPlane) {
  TableLocator locator(LocatorCamera(cell.camera), TagSpec{0.06, 0.0}, method);
  for (const PlacedTag& tag : cell.tags) {
    if (tag.id >= 100) locator.SetTagSpec(tag.id, TagSpec{0.05, kBeaconHeightM});
  }
  return locator;
}

// Ray-plane vs pose estimate over several cells (seeds 61..65), textured table and image noise.
// Ray-plane is the default because it is about ten times more accurate here: the centre pixel
// is good to ~0.1 px (~0.25 mm at 1 m), whereas the pose's depth comes from a 20-pixel tag's
// apparent size, and a depth error moves an off-axis tag sideways as well.
TEST(ApriltagTableLocatorTest, RecoversTablePositionsWithinMillimetres) {
  double ray_sq = 0.0, pose_sq = 0.0, ray_max = 0.0, pose_max = 0.0;
  int n = 0;
  for (const uint64_t seed : {61u, 62u, 63u, 64u, 65u}) {
    const Cell cell = MakeCell(seed);
    SceneOptions options;
    options.textured_table = true;
    options.noise_sigma = 2.0;
    options.seed = seed;
    const RgbImage image = testing::RenderScene(cell.camera, cell.tags, {}, options);
    TagDetector detector;
    const std::vector<TagLocation> locations = CellLocator(cell).Locate(detector.Detect(image));
    std::map<int, TagLocation> by_id;
    for (const TagLocation& l : locations) by_id.emplace(l.id, l);
    ASSERT_EQ(by_id.size(), cell.tags.size()) << "seed " << seed;
    for (const PlacedTag& tag : cell.tags) {
      ASSERT_TRUE(by_id.count(tag.id)) << "seed " << seed << " tag " << tag.id;
      const TagLocation& l = by_id.at(tag.id);
      const double ray_error = (l.ray_plane_table_m - tag.center_m).norm();
      const double pose_error = (l.pose_estimate_table_m - tag.center_m).norm();
      EXPECT_LT(ray_error, 0.002) << "seed " << seed << " tag " << tag.id;
      EXPECT_LT(pose_error, 0.015) << "seed " << seed << " tag " << tag.id;
      EXPECT_EQ(l.position_table_m, l.ray_plane_table_m);
      EXPECT_LT(l.disagreement_m, 0.015);
      ray_sq += ray_error * ray_error;
      pose_sq += pose_error * pose_error;
      ray_max = std::max(ray_max, ray_error);
      pose_max = std::max(pose_max, pose_error);
      ++n;
    }
  }
  const double ray_rms = std::sqrt(ray_sq / n), pose_rms = std::sqrt(pose_sq / n);
  std::cout << n << " tags: ray-plane rms " << ray_rms * 1e3 << " mm (max " << ray_max * 1e3
            << "), pose estimate rms " << pose_rms * 1e3 << " mm (max " << pose_max * 1e3 << ")\n";
  EXPECT_LT(ray_rms, 0.001);
  EXPECT_LT(ray_rms, pose_rms);
}

TEST(ApriltagTableLocatorTest, PoseEstimateMethodReportsThePoseAnswer) {
  const Cell cell = MakeCell(71);
  const RgbImage image = testing::RenderScene(cell.camera, cell.tags, {}, {});
  TagDetector detector;
  const std::vector<TagDetection> detections = detector.Detect(image);
  ASSERT_EQ(detections.size(), cell.tags.size());
  const TableLocator locator = CellLocator(cell, LocateMethod::kPoseEstimate);
  EXPECT_EQ(locator.method(), LocateMethod::kPoseEstimate);
  for (const TagLocation& l : locator.Locate(detections)) {
    EXPECT_EQ(l.position_table_m, l.pose_estimate_table_m);
    const double expected_z = l.id >= 100 ? kBeaconHeightM : 0.0;
    EXPECT_NEAR(l.position_table_m.z(), expected_z, 0.015) << "tag " << l.id;
  }
}

// The quality figure: with a wrong height (a beacon declared flat on the table), ray-plane and
// pose estimate part by centimetres, while with the right height they agree to millimetres.
TEST(ApriltagTableLocatorTest, DisagreementFlagsAWrongTagHeight) {
  const Cell cell = MakeCell(81);
  const RgbImage image = testing::RenderScene(cell.camera, cell.tags, {}, {});
  TagDetector detector;
  const std::vector<TagDetection> detections = detector.Detect(image);
  const TableLocator right = CellLocator(cell);
  TableLocator wrong(LocatorCamera(cell.camera), TagSpec{0.06, 0.0});
  for (const PlacedTag& tag : cell.tags) {
    if (tag.id >= 100) wrong.SetTagSpec(tag.id, TagSpec{0.05, 0.0});
  }
  int beacons = 0;
  for (const TagDetection& d : detections) {
    const double good = right.Locate(d).disagreement_m;
    const double bad = wrong.Locate(d).disagreement_m;
    EXPECT_LT(good, 0.01) << "tag " << d.id;
    if (d.id >= 100) {
      EXPECT_GT(bad, 0.03) << "tag " << d.id;
      ++beacons;
    } else {
      EXPECT_DOUBLE_EQ(bad, good) << "tag " << d.id;
    }
  }
  EXPECT_EQ(beacons, 5);
}

}  // namespace
}  // namespace recon::tags
