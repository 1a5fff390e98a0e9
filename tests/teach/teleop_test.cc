// The teacher's side of recording in the simulated cell: Cartesian teleop (what the studio's
// keyboard and gamepad drive), play data sample by sample, and the health of a reading stream.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/teach/play_recorder.h"
#include "engine/teach/recorder.h"
#include "engine/teach/stream_health.h"

namespace recon::teach {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<worlds::Tabletop> MakeTabletop() {
  worlds::TabletopOptions options;
  options.noise_sigma_m = 0.05;
  return std::make_unique<worlds::Tabletop>(options, std::make_unique<render::MujocoRenderer>());
}

TEST(CartesianTeleop, HoldingStillSendsNoMotionAndTheGripperAsCommanded) {
  auto world = MakeTabletop();
  world->Reset(3);
  TeleopCommand command;
  command.close_gripper = true;
  const std::vector<float> u = CartesianTeleopAction(*world, command);
  ASSERT_EQ(u.size(), 7u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(u[i], 0.0f) << "joint " << i;
  EXPECT_EQ(u[6], 1.0f);
  command.close_gripper = false;
  command.velocity_m_s = {NAN, 0, 0};  // a broken device: hold still, do not throw
  EXPECT_EQ(CartesianTeleopAction(*world, command)[0], 0.0f);
}

// Each axis, both ways: the grip point goes where the key says, by about the commanded distance,
// and not far off the line.
TEST(CartesianTeleop, MovesTheGripAlongEachAxis) {
  auto world = MakeTabletop();
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      world->Reset(5);
      // Start from a pose with room in every direction.
      TeleopCommand command;
      command.velocity_m_s = {0, 0, -0.1};
      for (int i = 0; i < 10; ++i) world->Step(CartesianTeleopAction(*world, command));
      const Eigen::Vector3d start = world->arm().GripPosition();
      command.velocity_m_s = Eigen::Vector3d::Zero();
      command.velocity_m_s[axis] = 0.1 * sign;
      for (int i = 0; i < 10; ++i) world->Step(CartesianTeleopAction(*world, command));
      const Eigen::Vector3d moved = world->arm().GripPosition() - start;
      EXPECT_NEAR(moved[axis], 0.1 * sign, 0.03) << "axis " << axis << " sign " << sign;
      Eigen::Vector3d off = moved;
      off[axis] = 0;
      EXPECT_LT(off.norm(), 0.02) << "axis " << axis << " sign " << sign;
    }
  }
}

TEST(CartesianTeleop, NeverDrivesTheFingersIntoTheTable) {
  auto world = MakeTabletop();
  world->Reset(2);
  TeleopCommand command;
  command.velocity_m_s = {0, 0, -0.3};
  for (int i = 0; i < 40; ++i) world->Step(CartesianTeleopAction(*world, command));
  EXPECT_GT(world->arm().GripPosition().z(), 0.0);
  EXPECT_LT(world->arm().GripPosition().z(), 0.03);  // it did go all the way down
}

// A person (here a proportional controller on the same commands a keyboard sends) teaches the
// whole task through the teleop: pick the toast, carry it to the plate, let go.
TEST(CartesianTeleop, ATeleoperatedDemonstrationSucceedsAndIsRecorded) {
  auto world = MakeTabletop();
  TeleopCommand command;
  DemoRecorder recorder(*world, CartesianTeleopTeacher(*world, &command), "keyboard");
  recorder.Start(4);
  const Eigen::Vector3d toast = world->ToastPosition();
  const Eigen::Vector3d plate = world->PlatePosition();
  struct Waypoint {
    Eigen::Vector3d at;
    bool close;
  };
  const std::vector<Waypoint> plan = {{toast + Eigen::Vector3d(0, 0, 0.12), false},
                                      // Down onto the slice, pressing toward the table.
                                      {toast - Eigen::Vector3d(0, 0, 0.004), false},
                                      {toast - Eigen::Vector3d(0, 0, 0.004), true},
                                      {toast + Eigen::Vector3d(0, 0, 0.12), true},
                                      {plate + Eigen::Vector3d(0, 0, 0.12), true},
                                      {plate + Eigen::Vector3d(0, 0, 0.05), true},
                                      {plate + Eigen::Vector3d(0, 0, 0.05), false},
                                      {plate + Eigen::Vector3d(0, 0, 0.25), false}};
  size_t next = 0;
  int dwell = 0;
  while (recorder.recording() && next < plan.size()) {
    const Eigen::Vector3d error = plan[next].at - world->arm().GripPosition();
    Eigen::Vector3d v = 2.0 * error;
    if (v.norm() > 0.15) v *= 0.15 / v.norm();
    command.velocity_m_s = error.norm() < 0.002 ? Eigen::Vector3d::Zero() : v;
    command.close_gripper = plan[next].close;
    // A waypoint is reached when near it; a person waits there for the gripper (its fingers
    // take up to 0.6 s to close on the slice).
    if (error.norm() < 0.01 && ++dwell >= 8) {
      ++next;
      dwell = 0;
    }
    command.finish = next == plan.size();
    recorder.Tick();
  }
  const store::DemoRecord record = recorder.Take();
  EXPECT_TRUE(world->TaskSucceeded())
      << "toast " << world->ToastPosition().transpose() << " plate " << plate.transpose();
  EXPECT_TRUE(record.meta.succeeded);
  EXPECT_EQ(record.meta.source, "keyboard");
  EXPECT_GT(record.meta.num_samples, 20u);
  EXPECT_LT(record.meta.num_samples, 200u);
  // The teacher's actions are what was recorded, with the beacon reading beside them.
  ASSERT_FALSE(record.episode.samples.empty());
  EXPECT_EQ(record.episode.samples.front().b.size(), 2u);
  EXPECT_EQ(record.episode.samples.front().u.size(), 7u);
}

TEST(PlayRecorder, RecordsSampleBySampleWhatAChunkRecords) {
  auto world = MakeTabletop();
  PlayRecorder recorder(*world, "simulated-play");
  StartSessionPlay(recorder, *world, 17, 3, 4);
  EXPECT_EQ(recorder.last(), nullptr);
  int ticks = 0;
  while (recorder.recording()) {
    recorder.Tick();
    ++ticks;
    ASSERT_NE(recorder.last(), nullptr);
  }
  EXPECT_EQ(ticks, 4);
  const store::PlayRecord ticked = recorder.Take();
  const store::PlayRecord chunk = RecordSessionPlayChunk(*world, 17, 3, 4);
  ASSERT_EQ(ticked.samples.size(), 4u);
  ASSERT_EQ(chunk.samples.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ticked.samples[i].y, chunk.samples[i].y) << i;
    EXPECT_EQ(ticked.samples[i].b, chunk.samples[i].b) << i;
  }
  EXPECT_EQ(ticked.meta.num_samples, 4u);
  EXPECT_NEAR(ticked.meta.teaching_seconds, 0.4, 1e-9);
  // The bowl moves between samples: the images differ while the plate's beacon stays put.
  EXPECT_NE(ticked.samples[0].y, ticked.samples[1].y);
  try {
    recorder.Start(1, 0);
    FAIL() << "a chunk of 0 samples was accepted";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("at least one sample"));
  }
}

// The paper's teacher recorded play around the plate's marked places, as the demonstrations
// showed them; `recon experiment` records play in each demonstration's scene. A session's play
// chunk k is recorded in demonstration k's scene, so play covers both plate sides as the
// demonstrations do (chunks drawn from scenes of their own once put the plate on one side in 7
// of 8 chunks).
TEST(PlayRecorder, ASessionsPlayChunkIsRecordedInItsDemonstrationsScene) {
  auto world = MakeTabletop();
  ASSERT_EQ(world->DemosPerConfiguration(), 2);
  DemoRecorder demo(*world, ScriptedTeacher, "scripted-teleop");
  PlayRecorder play(*world, "simulated-play");
  constexpr uint64_t kSessionSeed = 5;
  int left = 0;
  for (int k = 0; k < 8; ++k) {
    StartSessionDemo(demo, *world, kSessionSeed, k);
    const Eigen::Vector3d plate = world->PlatePosition(), bowl = world->BowlPosition();
    const int side = world->PlateSide();
    StartSessionPlay(play, *world, kSessionSeed, k, 3);
    EXPECT_EQ(world->PlatePosition(), plate) << k;
    EXPECT_EQ(world->BowlPosition(), bowl) << k << ": the play starts from the scene as it was";
    EXPECT_EQ(world->PlateSide(), side) << k;
    left += side > 0 ? 1 : 0;
    while (play.Tick()) {
    }
    const store::PlayRecord chunk = play.Take();
    EXPECT_EQ(chunk.meta.seed, store::Session::ScenarioSeed(kSessionSeed, k, true)) << k;
    ASSERT_EQ(chunk.samples.size(), 3u);
    // The beacon reports the plate of the demonstration's scene (5 cm noise per axis).
    for (const PlaySample& sample : chunk.samples) {
      EXPECT_LT(std::hypot(sample.b[0] - plate.x(), sample.b[1] - plate.y()), 0.3) << k;
    }
  }
  EXPECT_EQ(left, 4) << "the plate on each side in half the chunks, as in the demonstrations";
}

TEST(StreamHealth, ASteadyStreamHasItsRateAndNoDropouts) {
  StreamHealth health(10.0, 3.0);
  for (int i = 0; i <= 50; ++i) health.Add(i * 0.1, {1.0f, 2.0f});
  const StreamStats stats = health.Stats(5.0);
  EXPECT_NEAR(stats.rate_hz, 10.0, 0.01);
  EXPECT_EQ(stats.dropout_fraction, 0.0);
  EXPECT_EQ(stats.noise, 0.0);
  EXPECT_EQ(stats.received, 31);  // 2.0 .. 5.0 s
  EXPECT_NEAR(stats.seconds_since_last, 0.0, 1e-9);
}

TEST(StreamHealth, CountsMissingUpdatesAndMeasuresTheSpread) {
  StreamHealth health(10.0, 3.0);
  int received = 0;
  for (int i = 0; i <= 30; ++i) {
    if (i >= 10 && i < 15) continue;  // five updates lost
    // x alternates +-1 cm about 0.5 m: a standard deviation of about 1 cm.
    health.Add(i * 0.1, {i % 2 == 0 ? 0.51f : 0.49f, 0.2f});
    ++received;
  }
  const StreamStats stats = health.Stats(3.0);
  EXPECT_EQ(stats.received, received);
  EXPECT_NEAR(stats.dropout_fraction, 5.0 / (5.0 + received), 1e-9);
  EXPECT_NEAR(stats.noise, 0.01, 0.001);
  // It stops: after a second the missing updates count, after the window it is all dropouts.
  EXPECT_GT(health.Stats(4.0).dropout_fraction, stats.dropout_fraction);
  const StreamStats silent = health.Stats(7.0);
  EXPECT_EQ(silent.received, 0);
  EXPECT_EQ(silent.rate_hz, 0.0);
  EXPECT_EQ(silent.dropout_fraction, 1.0);
  EXPECT_NEAR(silent.seconds_since_last, 4.0, 1e-9);
  EXPECT_THROW(StreamHealth(0.0), UserError);
}

}  // namespace
}  // namespace recon::teach

namespace recon::teach {
namespace {

// The wrist turns about the vertical where the grip point stays, and stops at its limit; the
// jaw's closing axis turns with it, which is what lets a person line the fingers up.
TEST(CartesianTeleop, TurnsTheWristInPlaceUpToItsLimit) {
  auto world = MakeTabletop();
  world->Reset(5);
  const TeleopArm arm = TeleopArmOf(world->safety_limits());
  const Eigen::Vector3d start = world->arm().GripPosition();
  const Eigen::Vector3d axis_before = world->arm().AlignmentWith("toast")->closing_axis;
  EXPECT_NEAR(WristTurn(world->arm().JointPositions(), arm), 0.0, 1e-3);
  TeleopCommand command;
  command.wrist_turn_rad_s = kWristTurnSpeed_rad_s;
  for (int i = 0; i < 10; ++i) world->Step(CartesianTeleopAction(*world, command));
  const double turned = WristTurn(world->arm().JointPositions(), arm);
  EXPECT_NEAR(turned, kWristTurnSpeed_rad_s * 1.0, 0.1);
  EXPECT_LT((world->arm().GripPosition() - start).norm(), 0.01);
  const Eigen::Vector3d axis_after = world->arm().AlignmentWith("toast")->closing_axis;
  EXPECT_NEAR(std::acos(std::clamp(axis_before.dot(axis_after), -1.0, 1.0)), turned, 0.1);
  // Held on: it stops at the limit, however long the key is held.
  for (int i = 0; i < 60; ++i) world->Step(CartesianTeleopAction(*world, command));
  const double at_limit = WristTurn(world->arm().JointPositions(), arm);
  EXPECT_LE(at_limit, kMaxWristTurn_rad + 0.02);
  EXPECT_GT(at_limit, kMaxWristTurn_rad - 0.1);
  // And back the other way.
  command.wrist_turn_rad_s = -kWristTurnSpeed_rad_s;
  for (int i = 0; i < 10; ++i) world->Step(CartesianTeleopAction(*world, command));
  EXPECT_LT(WristTurn(world->arm().JointPositions(), arm), at_limit - 0.3);
  command.wrist_turn_rad_s = NAN;  // a broken device: no turn
  const std::vector<float> u = CartesianTeleopAction(*world, command);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(u[i], 0.0f);
}

// What the readout tells a person about the toast across the open fingers: off the jaw's axis,
// and by how much, with the window the grasp itself uses.
TEST(GraspAlignment, SaysHowFarTheToastIsOffTheJawsAxis) {
  auto world = MakeTabletop();
  world->Reset(5);
  const auto a = world->arm().AlignmentWith("toast");
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(a->closing_axis.norm(), 1.0, 1e-9);
  // A 10 cm slice between fingers 12.8 cm apart: 1.4 cm either way along the closing axis, and
  // 4 cm along the faces (the slice's half-width less a finger's).
  EXPECT_NEAR(a->closing_window_m, 0.014, 0.002);
  EXPECT_NEAR(a->faces_window_m, 0.04, 0.002);
  EXPECT_FALSE(world->arm().AlignmentWith("no-such-body").has_value());
}

}  // namespace
}  // namespace recon::teach
