#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <atomic>
#include <exception>
#include <functional>
#include <latch>
#include <thread>
#include <vector>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/worlds/mujoco_model.h"
#include "tests/render/test_scene.h"

namespace recon::render {
namespace {

using ::recon::render::testing::FindBlob;
using ::recon::render::testing::IsGreen;
using ::recon::render::testing::IsGrey;
using ::recon::render::testing::IsRed;
using ::recon::render::testing::kBoxTop_m;
using ::recon::render::testing::kTestScene;
using ::recon::render::testing::ProjectTop;
using ::recon::worlds::MujocoModel;
using ::testing::HasSubstr;

std::string UserErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no UserError";
}

/// kTestScene with its offscreen buffer size set to `width` x `height`.
std::string TestSceneWithBuffer(int width, int height) {
  std::string xml = kTestScene;
  const std::string from = "offwidth=\"640\" offheight=\"480\"";
  xml.replace(
      xml.find(from), from.size(),
      "offwidth=\"" + std::to_string(width) + "\" offheight=\"" + std::to_string(height) + "\"");
  return xml;
}

MujocoModel TestScene() { return MujocoModel::FromString(kTestScene, "render test scene"); }

void MoveRedBox(MujocoModel& scene, double x, double y) {
  scene.data()->mocap_pos[0] = x;
  scene.data()->mocap_pos[1] = y;
  mj_forward(scene.model(), scene.data());
}

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    ASSERT_TRUE(HeadlessRenderingAvailable(&why)) << why;
    renderer_ = MujocoRendererFactory()();
    mj_forward(scene_.model(), scene_.data());
  }

  MujocoModel scene_ = TestScene();
  std::unique_ptr<worlds::SceneRenderer> renderer_;
};

TEST_F(RenderTest, RedBoxIsRedWhereItsProjectionFallsAndNowhereElse) {
  const RgbImage image = renderer_->Render(scene_, "top", 64, 64);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 64);
  ASSERT_EQ(image.rgb.size(), 64u * 64u * 3u);

  const auto expected = ProjectTop(0.3, -0.2, kBoxTop_m, 64, 64);
  EXPECT_TRUE(IsRed(image.Pixel(static_cast<int>(expected.row), static_cast<int>(expected.col))));
  const auto red = FindBlob(image, IsRed);
  EXPECT_NEAR(red.row, expected.row, 1.0);
  EXPECT_NEAR(red.col, expected.col, 1.0);
  // The box's 16 cm top seen from 1.9 m covers about 6.5 x 6.5 pixels.
  EXPECT_GT(red.count, 30);
  EXPECT_LT(red.count, 60);

  // The floor elsewhere: grey, in all four quadrants and at the centre.
  for (const auto& [x, y] : {std::pair{-0.5, -0.5}, {-0.5, 0.3}, {0.5, 0.5}, {0.5, -0.6}, {0, 0}}) {
    const auto p = ProjectTop(x, y, 0, 64, 64);
    const uint8_t* pixel = image.Pixel(static_cast<int>(p.row), static_cast<int>(p.col));
    EXPECT_TRUE(IsGrey(pixel)) << "floor at (" << x << ", " << y << ") is " << int{pixel[0]} << ","
                               << int{pixel[1]} << "," << int{pixel[2]};
  }
}

TEST_F(RenderTest, ImagesAreTopRowFirstAndNotMirrored) {
  const RgbImage image = renderer_->Render(scene_, "top", 64, 64);
  // World +y is the image's top: the green box (y = +0.6) is in the top rows, the red box
  // (y = -0.2) below the middle; world +x is the right: the red box (x = +0.3) right of centre.
  const auto green = FindBlob(image, IsGreen);
  ASSERT_GT(green.count, 0);
  EXPECT_LT(green.row, 16);
  EXPECT_NEAR(green.row, ProjectTop(0, 0.6, kBoxTop_m, 64, 64).row, 1.0);
  const auto red = FindBlob(image, IsRed);
  EXPECT_GT(red.row, 32);
  EXPECT_GT(red.col, 32);
}

TEST_F(RenderTest, NonSquareOddSizesKeepGeometryAndRowOrder) {
  // 3 * 63 bytes per row is not a multiple of 4 (OpenGL's default row alignment), and a wide
  // image widens the view horizontally, not vertically (MuJoCo's fovy is vertical).
  for (const auto& [width, height] : {std::pair{63, 47}, {101, 33}, {640, 480}}) {
    const RgbImage image = renderer_->Render(scene_, "top", width, height);
    ASSERT_EQ(image.rgb.size(), static_cast<size_t>(width) * height * 3);
    const auto expected = ProjectTop(0.3, -0.2, kBoxTop_m, width, height);
    const auto red = FindBlob(image, IsRed);
    const double tolerance = std::max(1.0, height / 64.0);
    EXPECT_NEAR(red.row, expected.row, tolerance) << width << "x" << height;
    EXPECT_NEAR(red.col, expected.col, tolerance) << width << "x" << height;
  }
}

TEST_F(RenderTest, MovingTheBoxMovesItInTheImage) {
  const RgbImage before = renderer_->Render(scene_, "top", 64, 64);
  MoveRedBox(scene_, -0.4, 0.1);
  const RgbImage after = renderer_->Render(scene_, "top", 64, 64);
  EXPECT_NE(before.rgb, after.rgb);
  const auto expected = ProjectTop(-0.4, 0.1, kBoxTop_m, 64, 64);
  const auto red = FindBlob(after, IsRed);
  EXPECT_NEAR(red.row, expected.row, 1.0);
  EXPECT_NEAR(red.col, expected.col, 1.0);
  const auto old = ProjectTop(0.3, -0.2, kBoxTop_m, 64, 64);
  EXPECT_TRUE(IsGrey(after.Pixel(static_cast<int>(old.row), static_cast<int>(old.col))));
}

TEST_F(RenderTest, SameStateGivesBitIdenticalImages) {
  const RgbImage first = renderer_->Render(scene_, "top", 64, 64);
  const RgbImage second = renderer_->Render(scene_, "top", 64, 64);
  EXPECT_EQ(first.rgb, second.rgb);

  // Also after the renderer switched to another model and back (its GPU copy is re-made), and
  // from a second renderer.
  MujocoModel other = TestScene();
  MoveRedBox(other, 0.0, 0.0);
  const RgbImage of_other = renderer_->Render(other, "top", 64, 64);
  EXPECT_NE(of_other.rgb, first.rgb);
  EXPECT_EQ(renderer_->Render(scene_, "top", 64, 64).rgb, first.rgb);
  EXPECT_EQ(MujocoRenderer().Render(scene_, "top", 64, 64).rgb, first.rgb);
}

TEST_F(RenderTest, ANewModelGetsItsOwnOffscreenBuffer) {
  // MuJoCo's GPU context is cached per model; one made for a 64x64 offscreen buffer must not be
  // reused for a scene drawn at 320x240.
  MujocoModel small_scene = MujocoModel::FromString(TestSceneWithBuffer(64, 64), "small buffer");
  mj_forward(small_scene.model(), small_scene.data());
  ASSERT_GT(FindBlob(renderer_->Render(small_scene, "top", 64, 64), IsRed).count, 30);

  const RgbImage image = renderer_->Render(scene_, "top", 320, 240);
  const auto expected = ProjectTop(0.3, -0.2, kBoxTop_m, 320, 240);
  const auto red = FindBlob(image, IsRed);
  EXPECT_NEAR(red.row, expected.row, 2.0);
  EXPECT_NEAR(red.col, expected.col, 2.0);
  EXPECT_TRUE(IsGrey(image.Pixel(230, 10)));  // far outside the small buffer
}

TEST_F(RenderTest, ShadowsAreOffForSpeed) {
  // The light, slanted 45 degrees, would cast the 10 cm tall red box's shadow on the floor up to
  // 10 cm right (+x) of it.
  const RgbImage image = renderer_->Render(scene_, "top", 256, 256);
  const auto beside = ProjectTop(0.3 + 0.08 + 0.06, -0.2, 0, 256, 256);
  const auto far_away = ProjectTop(-0.5, -0.5, 0, 256, 256);
  const uint8_t* a = image.Pixel(static_cast<int>(beside.row), static_cast<int>(beside.col));
  const uint8_t* b = image.Pixel(static_cast<int>(far_away.row), static_cast<int>(far_away.col));
  EXPECT_TRUE(IsGrey(a)) << int{a[0]} << "," << int{a[1]} << "," << int{a[2]};
  EXPECT_NEAR(a[0], b[0], 3);
}

TEST_F(RenderTest, AnotherCameraSeesAnotherView) {
  const RgbImage top = renderer_->Render(scene_, "top", 64, 64);
  const RgbImage side = renderer_->Render(scene_, "side", 64, 64);
  EXPECT_NE(top.rgb, side.rgb);
  EXPECT_GT(FindBlob(side, IsRed).count, 0);
}

TEST_F(RenderTest, UnknownCameraNamesTheSceneAndItsCameras) {
  const std::string message = UserErrorOf([&] { renderer_->Render(scene_, "front", 64, 64); });
  EXPECT_THAT(message, HasSubstr("no camera \"front\""));
  EXPECT_THAT(message, HasSubstr("render test"));
  EXPECT_THAT(message, HasSubstr("\"top\", \"side\""));

  MujocoModel blind = MujocoModel::FromString(
      "<mujoco><worldbody><geom type=\"sphere\" size=\"1\"/></worldbody></mujoco>", "blind");
  EXPECT_THAT(UserErrorOf([&] { renderer_->Render(blind, "top", 64, 64); }),
              HasSubstr("it has no cameras"));
}

TEST_F(RenderTest, OversizeRequestsNameBothSizes) {
  std::string message = UserErrorOf([&] { renderer_->Render(scene_, "top", 800, 600); });
  EXPECT_THAT(message, HasSubstr("800x600"));
  EXPECT_THAT(message, HasSubstr("640x480"));
  EXPECT_THAT(message, HasSubstr("offwidth"));
  EXPECT_THAT(UserErrorOf([&] { renderer_->Render(scene_, "top", 640, 481); }),
              HasSubstr("640x481"));
  EXPECT_THAT(UserErrorOf([&] { renderer_->Render(scene_, "top", 0, 64); }), HasSubstr("0x64"));
  // The largest allowed size works.
  EXPECT_EQ(renderer_->Render(scene_, "top", 640, 480).rgb.size(), 640u * 480u * 3u);
}

TEST_F(RenderTest, MujocoErrorsWhileRenderingAreExceptionsAndTheRendererRecovers) {
  // A scene whose offscreen buffer is larger than any OpenGL renderbuffer: MuJoCo reports it
  // through mju_error while making its context, which must arrive here as an exception instead
  // of "press Enter to exit".
  MujocoModel huge_scene = MujocoModel::FromString(TestSceneWithBuffer(99999, 480), "huge buffer");
  mj_forward(huge_scene.model(), huge_scene.data());
  try {
    renderer_->Render(huge_scene, "top", 64, 64);
    ADD_FAILURE() << "rendering with a 99999-pixel-wide offscreen buffer did not throw";
  } catch (const worlds::MujocoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("Offscreen framebuffer"));
  }
  // The renderer is fine for an ordinary scene afterwards.
  const RgbImage image = renderer_->Render(scene_, "top", 64, 64);
  EXPECT_GT(FindBlob(image, IsRed).count, 30);
}

TEST(RenderThreadsTest, TwoRenderersOnTwoThreadsRenderAtTheSameTime) {
  // The reference images, rendered one after another on this thread.
  constexpr int kFrames = 40;
  const auto box_x = [](int thread, int frame) { return -0.5 + 0.025 * frame - 0.2 * thread; };
  std::vector<std::vector<RgbImage>> expected(2);
  {
    MujocoRenderer renderer;
    MujocoModel scene = TestScene();
    for (int t = 0; t < 2; ++t) {
      for (int f = 0; f < kFrames; ++f) {
        MoveRedBox(scene, box_x(t, f), 0.1 * t);
        expected[t].push_back(renderer.Render(scene, "top", 64, 64));
      }
    }
  }

  std::vector<std::vector<RgbImage>> actual(2);
  std::vector<std::exception_ptr> errors(2);
  std::latch start(2);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      try {
        // Each thread makes its renderer (and so its context) and its own mjData.
        auto renderer = MujocoRendererFactory()();
        MujocoModel scene = TestScene();
        start.arrive_and_wait();
        for (int f = 0; f < kFrames; ++f) {
          MoveRedBox(scene, box_x(t, f), 0.1 * t);
          actual[t].push_back(renderer->Render(scene, "top", 64, 64));
        }
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  }
  for (auto& thread : threads) thread.join();
  for (int t = 0; t < 2; ++t) {
    if (errors[t]) std::rethrow_exception(errors[t]);
    ASSERT_EQ(actual[t].size(), static_cast<size_t>(kFrames));
    for (int f = 0; f < kFrames; ++f) {
      EXPECT_EQ(actual[t][f].rgb, expected[t][f].rgb) << "thread " << t << " frame " << f;
    }
  }
  EXPECT_NE(actual[0][0].rgb, actual[1][0].rgb);
}

}  // namespace
}  // namespace recon::render
