// The teacher's 3-D view of the tabletop: the free camera and its limits, its pinhole model
// (OrbitSceneCamera) puts a point where MuJoCo draws it, and the world says what the gripper
// holds, at what heights it grasps, and where the drop line lands.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "devices/cell/scene_camera.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/worlds/orbit_camera.h"
#include "engine/worlds/tabletop.h"

namespace recon::worlds {
namespace {

struct Centroid {
  double x = 0, y = 0;
  int pixels = 0;
};

// Where the magenta pixels (a marker; nothing in the scene is magenta) are.
Centroid MagentaCentroid(const RgbImage& image) {
  Centroid c;
  for (int r = 0; r < image.height; ++r) {
    for (int col = 0; col < image.width; ++col) {
      const uint8_t* p = image.Pixel(r, col);
      if (p[0] > 150 && p[2] > 150 && p[1] < 90) {
        c.x += col + 0.5;
        c.y += r + 0.5;
        ++c.pixels;
      }
    }
  }
  if (c.pixels > 0) {
    c.x /= c.pixels;
    c.y /= c.pixels;
  }
  return c;
}

std::unique_ptr<Tabletop> TeacherViewTabletop() {
  TabletopOptions options;
  auto world = std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
  world->ResetToLayout(1, {0.56, 0.33, 0.0}, {0.6, -0.25, 0.0});
  return world;
}

// From every side and height, a small flat marker on the table is drawn where the pinhole model
// of the same free camera projects its centre: what the Record screen's crosshair and the
// scripted person rely on.
TEST(TeacherViewTest, TheFreeCamerasPinholeModelProjectsWhereMuJoCoDrawsIt) {
  auto world = TeacherViewTabletop();
  render::MujocoRenderer renderer;
  const Eigen::Vector3d point(0.8, -0.05, 0.0006);  // nothing stands between it and any camera
  for (const auto& [azimuth, elevation, distance] :
       {std::tuple{90.0, -35.0, 1.3}, std::tuple{-90.0, -35.0, 1.3}, std::tuple{180.0, -40.0, 1.5},
        std::tuple{90.0, -89.0, 1.3}, std::tuple{30.0, -20.0, 1.0}}) {
    OrbitCamera camera;
    camera.azimuth_deg = azimuth;
    camera.elevation_deg = elevation;
    camera.distance_m = distance;
    const std::vector<SceneMarker> markers = {
        {SceneMarker::Shape::kDisc, point, point, 0.015, {1.0f, 0.0f, 1.0f, 1.0f}}};
    const RgbImage image = renderer.RenderOrbit(world->scene(), camera, markers, 480, 360);
    const Centroid drawn = MagentaCentroid(image);
    ASSERT_GT(drawn.pixels, 4) << "azimuth " << azimuth << ", elevation " << elevation;
    const Eigen::Vector2d projected =
        cell::OrbitSceneCamera(world->scene(), camera, 480, 360).Project(point);
    EXPECT_NEAR(drawn.x, projected.x(), 0.5)
        << "azimuth " << azimuth << ", elevation " << elevation;
    EXPECT_NEAR(drawn.y, projected.y(), 0.5)
        << "azimuth " << azimuth << ", elevation " << elevation;
  }
}

// Whatever a drag or a wheel asks for, the camera stays above the table and at a distance that
// shows something; and the arrows' directions are the view's right and away along the table.
TEST(OrbitCameraTest, ItStaysWithinItsLimitsAndItsArrowsFollowTheView) {
  OrbitCamera c;
  c.azimuth_deg = 540;
  c.elevation_deg = 30;  // from below the table
  c.distance_m = 0.01;
  OrbitCamera clamped = c.Clamped();
  EXPECT_DOUBLE_EQ(clamped.azimuth_deg, 180);
  EXPECT_DOUBLE_EQ(clamped.elevation_deg, OrbitCamera::kMaxElevation_deg);
  EXPECT_DOUBLE_EQ(clamped.distance_m, OrbitCamera::kMinDistance_m);
  c.azimuth_deg = std::nan("");
  c.elevation_deg = -1e9;
  c.distance_m = std::numeric_limits<double>::infinity();
  clamped = c.Clamped();
  EXPECT_DOUBLE_EQ(clamped.azimuth_deg, OrbitCamera{}.azimuth_deg);
  EXPECT_DOUBLE_EQ(clamped.elevation_deg, OrbitCamera::kMinElevation_deg);
  EXPECT_DOUBLE_EQ(clamped.distance_m, OrbitCamera{}.distance_m);

  for (double azimuth : {-135.0, 0.0, 45.0, 90.0, 180.0}) {
    OrbitCamera view;
    view.azimuth_deg = azimuth;
    view.elevation_deg = -30;
    const Eigen::Matrix3d r = view.Rotation();
    EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
    // Right on screen is the camera's x; away is its forward direction, along the table.
    EXPECT_NEAR((view.TableRight() - r.col(0).head<2>().normalized()).norm(), 0, 1e-12);
    EXPECT_NEAR((view.TableAway() - (-r.col(2)).head<2>().normalized()).norm(), 0, 1e-12);
    // It looks at its look-at point from `distance` away.
    EXPECT_NEAR((view.Position() - view.lookat).norm(), view.distance_m, 1e-12);
  }
}

// The readout's facts: open, closing, holding the toast, closed on nothing; the heights at which
// a grasp holds (the tool floor to 5 mm below the slice's top); and the spot under the gripper on
// the toast's top, the table's, or the plate's.
TEST(TeacherViewTest, TheWorldSaysWhatTheGripHoldsAndWhereAGraspWorks) {
  auto world = TeacherViewTabletop();
  const auto [low, high] = world->GraspHeights();
  EXPECT_DOUBLE_EQ(low, 0.005);
  EXPECT_NEAR(high, 0.016 - 0.005, 1e-4);  // a 1.6 cm slice resting on the table
  EXPECT_EQ(world->GripOnToast(), ToastGrip::kOpen);
  // Over the table the spot lies on the table; over the toast (where the scripted teacher goes
  // first), on the toast's top.
  const auto over_toast = [&] {
    return (world->arm().GripPosition() - world->ToastPosition()).head<2>().norm() < 0.01;
  };
  if (!over_toast()) {
    EXPECT_NEAR(world->SurfaceBelowGrip().z(), 0.0, 1e-3);
  }
  for (int step = 0; step < Tabletop::kEpisodeLength && !over_toast(); ++step) {
    world->Step(world->ExpertAction());
  }
  ASSERT_TRUE(over_toast());
  EXPECT_NEAR(world->SurfaceBelowGrip().z(), 0.016, 1e-3);
  EXPECT_NEAR((world->SurfaceBelowGrip() - world->arm().GripPosition()).head<2>().norm(), 0, 1e-12);
  world->ResetToLayout(1, {0.56, 0.33, 0.0}, {0.6, -0.25, 0.0});

  // Closing high above the toast catches nothing.
  world->arm().CommandGripper(true);
  world->arm().Step(0.1);
  EXPECT_EQ(world->GripOnToast(), ToastGrip::kClosing);
  world->arm().Step(1.0);
  EXPECT_EQ(world->GripOnToast(), ToastGrip::kClosedOnNothing);

  // The scripted teacher grasps it.
  world->ResetToLayout(1, {0.56, 0.33, 0.0}, {0.6, -0.25, 0.0});
  bool held = false;
  for (int step = 0; step < Tabletop::kEpisodeLength && !held; ++step) {
    world->Step(world->ExpertAction());
    held = world->GripOnToast() == ToastGrip::kHolding;
  }
  ASSERT_TRUE(held);
  // Holding it, the spot shows where it will land: the table under it, not the toast itself.
  EXPECT_NEAR(world->SurfaceBelowGrip().z(), 0.0, 1e-3);
}

}  // namespace
}  // namespace recon::worlds
