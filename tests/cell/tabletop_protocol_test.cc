// The paper's protocol in the tabletop world: the two plate places, demonstrations two per
// configuration, the DWM1001's beacon noise, noise injected while demonstrating (DART), a slice
// of toast a real parallel gripper can hold, and the true-positions diagnostic.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/worlds/tabletop.h"
#include "engine/worlds/world_factory.h"

namespace recon::worlds {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<Tabletop> ProtocolTabletop(const std::string& layout, double noise = 0.0,
                                           const std::string& placement = "plate") {
  TabletopOptions options;
  options.placement = placement;
  options.layout = layout;
  options.noise_sigma_m = noise;
  return std::make_unique<Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

TEST(TabletopProtocolTest, PaperLayoutPutsThePlateAtOneOfTwoPlacesAndTheBowlAnywhere) {
  auto world = ProtocolTabletop("paper");
  std::set<int> sides;
  double bowl_min_y = 1, bowl_max_y = -1;
  for (uint64_t seed = 1; seed <= 20; ++seed) {  // seeds 1-20
    world->Reset(seed);
    const Eigen::Vector3d plate = world->PlatePosition();
    sides.insert(world->PlateSide());
    EXPECT_NEAR(plate.x(), 0.56, 0.0101) << "seed " << seed;
    EXPECT_NEAR(plate.y(), world->PlateSide() * 0.33, 0.0101) << "seed " << seed;
    bowl_min_y = std::min(bowl_min_y, world->BowlPosition().y());
    bowl_max_y = std::max(bowl_max_y, world->BowlPosition().y());
  }
  EXPECT_EQ(sides, (std::set<int>{-1, 1}));
  EXPECT_GT(bowl_max_y - bowl_min_y, 0.4) << "the bowl moves across the table";

  // The wide layout spreads the plate along the edge.
  auto wide = ProtocolTabletop("wide");
  double min_x = 1, max_x = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    wide->Reset(seed);
    min_x = std::min(min_x, wide->PlatePosition().x());
    max_x = std::max(max_x, wide->PlatePosition().x());
  }
  EXPECT_GT(max_x - min_x, 0.1);
}

TEST(TabletopProtocolTest, TakesOfAConfigurationShareTheSceneAndConfigurationsAlternateSides) {
  auto world = ProtocolTabletop("paper", Tabletop::kDwm1001NoiseSigma_m);
  EXPECT_EQ(world->DemosPerConfiguration(), 2);
  EXPECT_EQ(ProtocolTabletop("wide")->DemosPerConfiguration(), 1);
  // Seeds 11 and 12 are two takes of configuration 0 (scene seed 11), 13 one of configuration 1.
  world->ResetTake(11, 11, 0);
  const Eigen::Vector3d plate = world->PlatePosition(), bowl = world->BowlPosition();
  const std::vector<float> image = world->Observe().y;
  const std::vector<float> beacon_first_take = world->BeaconReading();
  EXPECT_EQ(world->PlateSide(), 1);
  world->ResetTake(12, 11, 0);
  EXPECT_EQ(world->PlatePosition(), plate);
  EXPECT_EQ(world->BowlPosition(), bowl);
  EXPECT_EQ(world->Observe().y, image);
  EXPECT_NE(world->BeaconReading(), beacon_first_take) << "each take has its own beacon noise";
  world->ResetTake(13, 13, 1);
  EXPECT_EQ(world->PlateSide(), -1);
  EXPECT_NE(world->BowlPosition(), bowl);
}

TEST(TabletopProtocolTest, RecordedDemonstrationsComeInConfigurationsOfTwo) {
  auto world = ProtocolTabletop("paper");
  const std::vector<uint64_t> seeds = {21, 22, 23, 24};  // 2 configurations
  const Dataset data = RecordDemonstrations(*world, seeds, 0);
  ASSERT_EQ(data.demos.size(), 4u);
  // Takes of one configuration start from the same image; the configurations differ.
  EXPECT_EQ(data.demos[0].samples[0].y, data.demos[1].samples[0].y);
  EXPECT_EQ(data.demos[2].samples[0].y, data.demos[3].samples[0].y);
  EXPECT_NE(data.demos[0].samples[0].y, data.demos[2].samples[0].y);

  CheckDemosFillConfigurations(*world, 4, "--demos");
  try {
    CheckDemosFillConfigurations(*world, 5, "--demos");
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--demos 5"));
    EXPECT_THAT(e.what(), HasSubstr("2 demonstrations per scene configuration"));
    EXPECT_THAT(e.what(), HasSubstr("2 full configurations and one with 1 take"));
    EXPECT_THAT(e.what(), HasSubstr("4 or 6"));
  }
  CheckDemosFillConfigurations(*ProtocolTabletop("wide"), 5, "--demos");  // one per scenario
}

TEST(TabletopProtocolTest, InjectedNoiseMovesTheArmButTheLabelsStayTheTeachers) {
  auto world = ProtocolTabletop("paper");
  const std::vector<uint64_t> seeds = {31, 32};
  const Dataset clean = RecordDemonstrations(*world, seeds, 0);
  const DemoNoise noise{0.05, 7};  // 0.05 rad/s, seed 7
  const Dataset noisy = RecordDemonstrations(*world, seeds, 0, noise);
  const Dataset again = RecordDemonstrations(*world, seeds, 0, noise);
  ASSERT_EQ(noisy.demos.size(), 2u);
  // Reproducible from its seed, and different from the clean recording.
  ASSERT_EQ(noisy.demos[0].samples.size(), again.demos[0].samples.size());
  for (size_t t = 0; t < noisy.demos[0].samples.size(); ++t) {
    ASSERT_EQ(noisy.demos[0].samples[t].x, again.demos[0].samples[t].x) << "step " << t;
  }
  EXPECT_NE(noisy.demos[0].samples[10].x, clean.demos[0].samples[10].x);
  // Takes of one configuration now differ (each take its own noise).
  EXPECT_NE(noisy.demos[0].samples[10].x, noisy.demos[1].samples[10].x);
  // The teacher still finishes, and the labels are the teacher's: replaying a noisy take's
  // states, the expert asks for exactly the stored actions.
  for (const Episode& e : noisy.demos) {
    EXPECT_LT(e.samples.size(), static_cast<size_t>(Tabletop::kEpisodeLength));
  }
  world->ResetTake(31, 31, 0);
  Rng rng(Rng::Derive(7, 31));
  for (size_t t = 0; t < noisy.demos[0].samples.size(); ++t) {
    const Sample& s = noisy.demos[0].samples[t];
    ASSERT_EQ(world->ExpertAction(), s.u) << "step " << t;
    world->Step(PerturbAction(*world, s.u, noise.sigma, rng));
  }
  // The gripper command is never perturbed.
  Rng check(3);
  const std::vector<float> u = {0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 1.0f};
  for (int i = 0; i < 100; ++i) EXPECT_EQ(PerturbAction(*world, u, 0.5, check)[6], 1.0f);
  EXPECT_EQ(PerturbAction(*world, u, 0.0, check), u);
  EXPECT_THROW(RecordDemonstrations(*world, seeds, 0, {-0.1, 1}), UserError);
  EXPECT_THROW(RecordDemonstrations(*world, seeds, 0, {std::nan(""), 1}), UserError);
}

TEST(TabletopProtocolTest, TheGripperHoldsTheToastOnlyWhereAParallelGripperWould) {
  auto world = ProtocolTabletop("paper", 0.0, "none");
  const Eigen::Vector3d toast = world->ToastPosition();
  struct Case {
    Eigen::Vector3d offset;  // of the grip point from the toast's centre
    bool held;
    const char* what;
  };
  const Case cases[] = {
      {{0, 0, 0}, true, "tips at the centre"},
      {{0, 0, -0.003}, true, "tips at the tool floor, 5 mm over the table"},
      {{0, 0, 0.002}, true, "tips 2 mm above the centre: the pads still grip 6 mm"},
      {{0, 0, 0.01}, false, "tips 1 cm above the centre: the pads close over the slice"},
      {{0, 0, 0.025}, false, "2.5 cm above"},
      {{0.0, 0.035, 0}, true, "3.5 cm along the finger faces: the pads are still on the slice"},
      {{0.0, 0.045, 0}, false, "4.5 cm along the finger faces: a pad misses the edge"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    world->Reset(1);
    const auto q = world->arm().SolveGraspIk(toast + c.offset, 0.0, Ur5Arm::kHome);
    ASSERT_TRUE(q.has_value());
    world->arm().Reset(*q);
    world->arm().CommandGripper(true);
    EXPECT_EQ(world->arm().HeldObject() >= 0, c.held);
  }
}

TEST(TabletopProtocolTest, FingersCloseAtTheirSpeedAndCatchWhatComesBetweenThem) {
  auto world = ProtocolTabletop("paper", 0.0, "none");
  world->Reset(2);
  const Eigen::Vector3d toast = world->ToastPosition();
  // Close 1 cm above the slice (outside the window), then bring the tips down into it while the
  // fingers are still on their way: the slice is caught.
  auto above = world->arm().SolveGraspIk(toast + Eigen::Vector3d(0, 0, 0.01), 0.0, Ur5Arm::kHome);
  auto at = world->arm().SolveGraspIk(toast, 0.0, Ur5Arm::kHome);
  ASSERT_TRUE(above && at);
  world->arm().Reset(*above);
  world->arm().CommandGripper(true);
  EXPECT_LT(world->arm().HeldObject(), 0);
  EXPECT_TRUE(world->arm().FingersClosing());
  world->arm().Step(0.1);
  // 50 mm/s: after 0.1 s the fingers have moved 5 of their 60 mm, the opening shows it.
  EXPECT_NEAR(world->arm().GripperOpening(), 55.0 / 60.0, 0.03);
  EXPECT_LT(world->arm().HeldObject(), 0);
  // Down into the window in 0.2 s, the fingers still closing.
  Ur5Joints qd;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) qd[i] = ((*at)[i] - (*above)[i]) / 0.2;
  world->arm().CommandJointVelocities(qd);
  world->arm().Step(0.25);
  EXPECT_GE(world->arm().HeldObject(), 0) << "caught on the way in";

  // Closed on nothing: once the fingers have arrived, bringing the slice between them no longer
  // helps.
  world->Reset(2);
  world->arm().Reset(*above);
  world->arm().CommandGripper(true);
  for (int i = 0; i < 8; ++i) world->arm().Step(0.1);
  EXPECT_FALSE(world->arm().FingersClosing());
  EXPECT_LT(world->arm().HeldObject(), 0);
}

TEST(TabletopProtocolTest, OutcomeDetailsTellWhetherAndHowTheGraspHappened) {
  auto world = ProtocolTabletop("paper", 0.0, "none");
  world->Reset(205);
  std::map<std::string, double> d = world->OutcomeDetails();
  EXPECT_EQ(d.at("grasped"), 0.0);
  EXPECT_GT(d.at("closest_approach_m"), 0.2) << "the arm starts at home, far above the toast";
  for (int t = 0; t < world->EpisodeLength(); ++t) world->Step(world->ExpertAction());
  d = world->OutcomeDetails();
  EXPECT_EQ(d.at("grasped"), 1.0);
  EXPECT_LT(d.at("closest_approach_m"), 0.01);
  EXPECT_LE(d.at("closes_on_nothing"), 1.0);
  // A policy that shuts the gripper in the air and never comes down.
  world->Reset(205);
  for (int t = 0; t < 20; ++t) {
    std::vector<float> u(7, 0.0f);
    u[6] = t % 4 < 2 ? 1.0f : 0.0f;  // close, open, close, ...
    world->Step(u);
  }
  d = world->OutcomeDetails();
  EXPECT_EQ(d.at("grasped"), 0.0);
  EXPECT_EQ(d.at("closes_on_nothing"), 5.0);
  EXPECT_GT(d.at("closest_approach_m"), 0.2);
}

TEST(TabletopProtocolTest, TheExpertSucceedsInEveryLayoutOfBothKinds) {
  for (const std::string layout : {"paper", "wide"}) {
    SCOPED_TRACE(layout);
    auto world = ProtocolTabletop(layout, 0.0, "none");
    int succeeded = 0;
    for (uint64_t seed = 200; seed < 220; ++seed) {  // seeds 200-219
      world->Reset(seed);
      for (int t = 0; t < world->EpisodeLength(); ++t) world->Step(world->ExpertAction());
      succeeded += world->TaskSucceeded() ? 1 : 0;
    }
    EXPECT_EQ(succeeded, 20);
  }
}

// A learner imitates the teacher's joint velocities only approximately. The teacher's descent
// must leave it room: an arm that follows the teacher's commands at 80 % of their speed (as a
// policy that under-fits them does) must still catch the toast at its first close, in every
// layout. Aiming at the slice's centre and closing 12 mm above it, the teacher itself had 0.3 mm
// to spare (docs/cell.md).
TEST(TabletopProtocolTest, ALearnerSlowerThanTheTeacherStillCatchesTheToastAtItsFirstClose) {
  auto world = ProtocolTabletop("paper", 0.0, "none");
  for (uint64_t seed = 300; seed < 310; ++seed) {  // seeds 300-309
    SCOPED_TRACE(seed);
    world->Reset(seed);
    for (int t = 0; t < world->EpisodeLength() && !world->TaskSucceeded(); ++t) {
      std::vector<float> u = world->ExpertAction();
      for (int j = 0; j < 6; ++j) u[j] *= 0.8f;
      world->Step(u);
    }
    const std::map<std::string, double> d = world->OutcomeDetails();
    EXPECT_EQ(d.at("grasped"), 1.0);
    EXPECT_EQ(d.at("closes_on_nothing"), 0.0);
    EXPECT_TRUE(world->TaskSucceeded());
  }
}

TEST(TabletopProtocolTest, TheDiagnosticObservesTheObjectsTruePositionsWithoutACamera) {
  CellResources cell;  // no renderer: the diagnostic draws nothing
  auto world = MakeWorld("tabletop-state", "plate", 0.0, false, cell);
  EXPECT_EQ(world->Spec().ToString(), "x 7, y 6, b 2, u 7");
  world->Reset(5);
  auto* tabletop = dynamic_cast<Tabletop*>(world.get());
  ASSERT_NE(tabletop, nullptr);
  const std::vector<float> y = world->Observe().y;
  ASSERT_EQ(y.size(), 6u);
  EXPECT_FLOAT_EQ(y[0], static_cast<float>(tabletop->ToastPosition().x()));
  EXPECT_FLOAT_EQ(y[3], static_cast<float>(tabletop->PlatePosition().y()));
  EXPECT_FLOAT_EQ(y[5], static_cast<float>(tabletop->BowlPosition().y()));
  EXPECT_THROW(MakeWorld("tabletop", "plate", 0.0, false, cell), UserError);
}

TEST(TabletopProtocolTest, BadLayoutAndNoiseAreNamed) {
  try {
    ProtocolTabletop("diagonal");
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown tabletop layout 'diagonal' (valid: paper, wide)"));
  }
  for (double bad : {-0.01, 0.6, std::nan("")}) {
    try {
      ProtocolTabletop("paper", bad);
      FAIL() << "expected UserError for " << bad;
    } catch (const UserError& e) {
      EXPECT_THAT(e.what(), HasSubstr("beacon noise must be between 0 and 0.5 metres"));
    }
  }
  EXPECT_EQ(DefaultBeaconNoise("tabletop"), 0.07);
  EXPECT_EQ(DefaultBeaconNoise("bintransfer"), 0.0);
  EXPECT_EQ(WorldLayouts("tabletop"), (std::vector<std::string>{"paper", "wide"}));
  EXPECT_TRUE(WorldLayouts("dynamic2d").empty());
}

}  // namespace
}  // namespace recon::worlds
