// SimulatedCamera in the simulated cell: 10 Hz stamps, consecutive numbers, images that follow
// the arm.

#include "devices/sim/simulated_camera.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "tests/sim/sim_test_support.h"

namespace recon::sim {
namespace {

using ::testing::HasSubstr;

int DifferentPixels(const RgbImage& a, const RgbImage& b) {
  int n = 0;
  for (int r = 0; r < a.height; ++r) {
    for (int c = 0; c < a.width; ++c) {
      const uint8_t* p = a.Pixel(r, c);
      const uint8_t* q = b.Pixel(r, c);
      n += (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) ? 1 : 0;
    }
  }
  return n;
}

TEST(SimulatedCameraTest, TenHertzFramesThatFollowTheArm) {
  auto cell = testing::MakeCell();
  cell->Reset(3);  // scenario seed 3
  SimulatedCamera& camera = cell->camera();
  EXPECT_EQ(camera.Describe(), "simulated top camera 64x64");

  devices::TeleopCommand still;
  devices::TeleopCommand swing;
  swing.joint_velocity_rad_s[0] = 0.6;  // the base turns: the arm sweeps across the view
  std::vector<devices::CameraFrame> frames;
  frames.push_back(camera.Capture());
  for (int step = 0; step < 20; ++step) {
    cell->Step(step < 5 ? still : swing);
    frames.push_back(camera.Capture());
  }
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].sequence, static_cast<int64_t>(i));
    EXPECT_NEAR(frames[i].timestamp_s, 0.1 * static_cast<double>(i), 1e-9);
    EXPECT_EQ(frames[i].image.width, 64);
    EXPECT_EQ(frames[i].image.height, 64);
  }
  // Holding still, the view holds still; once the base turns, every frame differs from the last.
  EXPECT_EQ(DifferentPixels(frames[1].image, frames[5].image), 0);
  for (size_t i = 7; i < frames.size(); ++i) {
    EXPECT_GT(DifferentPixels(frames[i - 1].image, frames[i].image), 5) << "frame " << i;
  }
  // The camera renders what the world's own camera image shows.
  EXPECT_EQ(frames.back().image.rgb, cell->world().CameraImage().rgb);
}

TEST(SimulatedCameraTest, BadCamerasAreUserErrors) {
  auto cell = testing::MakeCell();
  devices::ManualClock clock;
  try {
    SimulatedCamera camera(cell->world().scene(), "side", 64, 64,
                           std::make_unique<render::MujocoRenderer>(), clock);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no camera 'side'"));
    EXPECT_THAT(e.what(), HasSubstr("top, front"));
  }
  EXPECT_THROW(SimulatedCamera(cell->world().scene(), "top", 64, 64, nullptr, clock), UserError);
  EXPECT_THROW(SimulatedCamera(cell->world().scene(), "top", 0, 64,
                               std::make_unique<render::MujocoRenderer>(), clock),
               UserError);
}

}  // namespace
}  // namespace recon::sim
