// The tabletop world with the real offscreen renderer: what the camera shows, the scripted
// expert, determinism, beacons and play data.

#include "engine/worlds/tabletop.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "devices/render/mujoco_renderer.h"
#include "devices/tags/tag_detector.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/worlds/world_factory.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<Tabletop> MakeTabletop(const std::string& placement = "plate", double noise = 0.0,
                                       int size = 64) {
  TabletopOptions options;
  options.placement = placement;
  options.noise_sigma_m = noise;
  options.image_width = options.image_height = size;
  return std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

// Mean column (0..1 of the width) of the strongly blue pixels in the image's upper part (the
// plate stands at x 0.45-0.68 m, above the middle row; the blue-grey arm is in the lower part).
double BlueColumn(const RgbImage& image) {
  double sum = 0;
  int count = 0;
  for (int r = 0; r < image.height * 58 / 100; ++r) {
    for (int c = 0; c < image.width; ++c) {
      const uint8_t* p = image.Pixel(r, c);
      if (p[2] > 185 && p[0] < 110 && p[1] < 140) {  // the plate, not the blue-grey arm
        sum += (c + 0.5) / image.width;
        ++count;
      }
    }
  }
  return count > 0 ? sum / count : -1.0;
}

TEST(TabletopTest, SpecIsJointsImageBeaconAndJointVelocitiesWithGripper) {
  auto world = MakeTabletop();
  EXPECT_EQ(world->Spec().ToString(), "x 7, y 3x64x64, b 2, u 7");
  EXPECT_EQ(MakeTabletop("none", 0.0, 48)->Spec().ToString(), "x 7, y 3x48x48, b 0, u 7");
  world->Reset(5);
  const Observation o = world->Observe();
  EXPECT_EQ(o.x.size(), 7u);
  EXPECT_EQ(o.y.size(), 3u * 64 * 64);
}

TEST(TabletopTest, CameraSeesThePlateOnItsSide) {
  auto world = MakeTabletop();
  int left = 0, right = 0;
  for (uint64_t seed = 1; seed <= 12; ++seed) {  // seeds 1-12 cover both sides
    world->Reset(seed);
    const double column = BlueColumn(world->CameraImage());
    ASSERT_GE(column, 0.0) << "no plate in view, seed " << seed;
    // World +y (the plate's left side) is the image's left.
    if (world->PlateSide() > 0) {
      EXPECT_LT(column, 0.4) << "seed " << seed;
      ++left;
    } else {
      EXPECT_GT(column, 0.6) << "seed " << seed;
      ++right;
    }
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
}

TEST(TabletopTest, EveryAprilTagIsDetectedInADetailedFrame) {
  auto world = MakeTabletop();
  world->Reset(3);
  render::MujocoRenderer renderer;
  const RgbImage frame = renderer.Render(world->scene(), "top", 640, 480);
  tags::TagDetector detector;
  std::vector<int> ids;
  for (const auto& d : detector.Detect(frame)) ids.push_back(d.id);
  EXPECT_THAT(ids, ::testing::UnorderedElementsAre(0, 1, 2, 3, 10));
}

TEST(TabletopTest, ExpertPutsTheToastOnThePlate) {
  auto world = MakeTabletop("none");
  int succeeded = 0;
  for (uint64_t seed = 100; seed < 110; ++seed) {  // seeds 100-109
    world->Reset(seed);
    EXPECT_FALSE(world->TaskSucceeded());
    for (int t = 0; t < world->EpisodeLength(); ++t) world->Step(world->ExpertAction());
    succeeded += world->TaskSucceeded() ? 1 : 0;
    EXPECT_LT(world->EpisodeMetric(), Tabletop::kPlateRadius_m) << "seed " << seed;
    const auto details = world->OutcomeDetails();
    EXPECT_EQ(details.at("toast_moved"), 1.0);
    EXPECT_EQ(details.at("toast_held"), 0.0);
    EXPECT_EQ(details.at("grip_nearer_bowl"), 0.0) << "the expert ends above the plate";
  }
  EXPECT_EQ(succeeded, 10);
  // The expert stays well inside the safety envelope: its demonstrations are what it meant.
  EXPECT_EQ(world->safety_stats().changed, 0) << "of " << world->safety_stats().commands;
  EXPECT_EQ(world->safety_stats().commands, 10 * world->EpisodeLength());
}

TEST(TabletopTest, ASafetyEnvelopeStopsAPolicyThatOutputsGarbage) {
  auto world = MakeTabletop("none");
  world->Reset(7);
  Rng rng(31);  // seed 31: a policy gone wrong for a whole episode
  for (int t = 0; t < world->EpisodeLength(); ++t) {
    std::vector<float> u(7);
    for (float& x : u) {
      const double kind = rng.Uniform(0, 1);
      x = kind < 0.1   ? std::nanf("")
          : kind < 0.4 ? static_cast<float>(rng.Uniform(-1e30, 1e30))
                       : static_cast<float>(rng.Uniform(-3, 3));
    }
    world->Step(u);
    // The servo lags its command by a few millimetres; the floor is 5 mm over the table.
    ASSERT_GT(world->arm().GripPosition().z(), 0.0) << "step " << t;
  }
  const safety::SafetyStats& stats = world->safety_stats();
  EXPECT_GT(stats.non_finite, 0);
  EXPECT_GT(stats.velocity, 0);
  EXPECT_GT(stats.changed, world->EpisodeLength() / 2);
}

TEST(TabletopTest, RecordingStopsWhenTheTeacherIsDone) {
  auto world = MakeTabletop();
  const Dataset data = RecordDemonstrations(*world, {100, 101, 102}, 2);  // seeds 100-102
  ASSERT_EQ(data.demos.size(), 3u);
  EXPECT_EQ(data.play.size(), 6u);
  for (const Episode& e : data.demos) {
    EXPECT_GT(e.samples.size(), 40u);
    EXPECT_LT(e.samples.size(), static_cast<size_t>(Tabletop::kEpisodeLength));
    // The gripper command closes once and opens once: grasp, then release over the plate.
    int changes = 0;
    for (size_t t = 1; t < e.samples.size(); ++t) {
      changes += e.samples[t].u[6] != e.samples[t - 1].u[6] ? 1 : 0;
    }
    EXPECT_EQ(changes, 2);
  }
  EXPECT_TRUE(world->TaskSucceeded());
  EXPECT_TRUE(world->DemonstrationDone());
}

TEST(TabletopTest, SameSeedReproducesImagesAndExpertBitForBit) {
  auto a = MakeTabletop();
  auto b = MakeTabletop();
  a->Reset(42);
  b->Reset(42);
  for (int t = 0; t < 30; ++t) {
    ASSERT_EQ(a->Observe().y, b->Observe().y) << "step " << t;
    ASSERT_EQ(a->ExpertAction(), b->ExpertAction()) << "step " << t;
    a->Step(a->ExpertAction());
    b->Step(b->ExpertAction());
  }
  b->Reset(43);
  EXPECT_NE(a->BowlPosition(), b->BowlPosition());
}

TEST(TabletopTest, BeaconReportsThePlateBeaconWithTheRequestedNoise) {
  auto exact = MakeTabletop("plate", 0.0);
  exact->Reset(7);
  const std::vector<float> b = exact->BeaconReading();
  ASSERT_EQ(b.size(), 2u);
  EXPECT_NEAR(b[0], exact->BeaconPosition().x(), 1e-6);
  EXPECT_NEAR(b[1], exact->BeaconPosition().y(), 1e-6);
  EXPECT_LT((exact->BeaconPosition() - exact->PlatePosition()).head<2>().norm(), 0.2);

  auto noisy = MakeTabletop("plate", 0.1);
  noisy->Reset(7);
  double sum_sq = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const std::vector<float> r = noisy->BeaconReading();
    sum_sq += std::pow(r[0] - noisy->BeaconPosition().x(), 2);
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n), 0.1, 0.01);
  EXPECT_TRUE(MakeTabletop("none")->BeaconReading().empty());
}

TEST(TabletopTest, PlayMovesTheBowlWhileTheBeaconReportsThePlate) {
  auto world = MakeTabletop();
  world->Reset(9);
  const Eigen::Vector3d bowl = world->BowlPosition();
  const std::vector<float> image = world->Observe().y;
  const PlaySample play = world->SamplePlay();
  EXPECT_EQ(play.x.size(), 7u);
  EXPECT_EQ(play.y.size(), image.size());
  EXPECT_NE(play.y, image) << "the bowl moved in the play image";
  ASSERT_EQ(play.b.size(), 2u);
  EXPECT_NEAR(play.b[0], world->BeaconPosition().x(), 1e-6);
  // The scenario itself is unchanged.
  EXPECT_EQ(world->BowlPosition(), bowl);
  EXPECT_EQ(world->Observe().y, image);
}

TEST(TabletopTest, UnreachableLayoutIsAClearErrorAndAReachableOneIsKept) {
  auto world = MakeTabletop();
  world->ResetToLayout(4, {0.6, -0.33, 0.0}, {0.4, 0.3, 0.0});
  EXPECT_EQ(world->PlateSide(), -1);
  EXPECT_NEAR(world->PlatePosition().x(), 0.6, 1e-12);
  try {
    world->ResetToLayout(4, {1.3, 0.33, 0.0}, {0.4, -0.3, 0.0});  // beyond the arm's reach
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot reach"));
    EXPECT_THAT(e.what(), HasSubstr("1.300"));
  }
}

TEST(TabletopTest, BadOptionsAreUserErrors) {
  TabletopOptions options;
  options.placement = "bowl";
  try {
    Tabletop world(options, std::make_unique<render::MujocoRenderer>());
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("none, plate"));
  }
  options.placement = "plate";
  EXPECT_THROW(Tabletop(options, nullptr), UserError);
  options.image_width = 8;
  EXPECT_THROW(Tabletop(options, std::make_unique<render::MujocoRenderer>()), UserError);
}

TEST(TabletopTest, FactoryBuildsItWithARendererFactory) {
  CellResources cell;
  cell.renderer_factory = render::MujocoRendererFactory();
  cell.image_size = 32;
  auto world = MakeWorld("tabletop", "plate", 0.0, false, cell);
  EXPECT_EQ(world->Spec().ToString(), "x 7, y 3x32x32, b 2, u 7");
  EXPECT_TRUE(world->HasSuccess());
}

}  // namespace
}  // namespace recon::worlds
