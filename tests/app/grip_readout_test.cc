// The Record screen's grip readout (ui::ReadGrip) on the simulated tabletop's own facts
// (studio::GripViewOf), in every grip state: open far from the toast, above it, low enough, off
// the jaw's axis, beside it at the table, closing, holding and lifted, closed on nothing. The
// arm is driven by the same Cartesian teleop a person's keys drive.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "app/studio/cell_view.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/worlds/tabletop.h"
#include "ui/screens/grip_readout.h"

namespace recon::studio {
namespace {

using ui::GripState;

class GripReadoutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    world_ = std::make_unique<worlds::Tabletop>(worlds::TabletopOptions{},
                                                std::make_unique<render::MujocoRenderer>());
    world_->ResetToLayout(1, kToast, kPlate);
  }

  /// Drives the grip point to `target` (table frame) as a held key would, the gripper as
  /// `closed` says; true when it got within 1 mm.
  bool MoveGripTo(const Eigen::Vector3d& target, bool closed = false) {
    for (int step = 0; step < 400; ++step) {
      const Eigen::Vector3d off = target - world_->arm().GripPosition();
      if (off.norm() < 0.001) return true;
      teach::TeleopCommand command;
      // The rest of the way in one period, at most a held key's 0.1 m/s.
      Eigen::Vector3d velocity = off / 0.1;
      if (velocity.norm() > 0.1) velocity *= 0.1 / velocity.norm();
      command.velocity_m_s = velocity;
      command.close_gripper = closed;
      world_->Step(teach::CartesianTeleopAction(*world_, command));
    }
    return false;
  }
  void Hold(double seconds, bool closed) {
    teach::TeleopCommand command;
    command.close_gripper = closed;
    for (int i = 0; i < static_cast<int>(seconds / 0.1); ++i) {
      world_->Step(teach::CartesianTeleopAction(*world_, command));
    }
  }
  ui::GripReadout Read(ui::TeleopMode teleop = ui::TeleopMode::kKeyboard) const {
    ui::StudioSnapshot s;
    s.teleop = teleop;
    s.grip = GripViewOf(*world_);
    const Eigen::Vector3d grip = world_->arm().GripPosition();
    s.grip_m = {static_cast<float>(grip.x()), static_cast<float>(grip.y()),
                static_cast<float>(grip.z())};
    s.gripper_closed = world_->arm().GripperClosed();
    return s.grip.state == GripState::kUnknown ? ui::GripReadout{} : ui::ReadGrip(s);
  }
  GripState State() const { return GripViewOf(*world_).state; }
  Eigen::Vector3d ToastTop(double above_m) const {
    Eigen::Vector3d p = world_->ToastPosition();
    p.z() = above_m;
    return p;
  }
  double BandMiddle() const {
    const auto [low, high] = world_->GraspHeights();
    return 0.5 * (low + high);
  }

  static inline const Eigen::Vector3d kToast{0.56, 0.33, 0.0}, kPlate{0.6, -0.25, 0.0};
  std::unique_ptr<worlds::Tabletop> world_;
};

TEST_F(GripReadoutTest, OpenFarFromTheToastItGivesTheBandAndNoHint) {
  const ui::GripReadout r = Read();
  EXPECT_EQ(r.state, "Gripper open");
  EXPECT_NE(r.height.find("it grasps the toast at 0.5-1.1 cm"), std::string::npos) << r.height;
  EXPECT_EQ(r.hint, "");
}

TEST_F(GripReadoutTest, AboveTheToastItSaysHowMuchLowerAndThenThatItIsLowEnough) {
  const auto [low, high] = world_->GraspHeights();
  ASSERT_TRUE(MoveGripTo(ToastTop(high + 0.03)));
  EXPECT_EQ(Read().hint, "lower 3.0 cm more before closing");
  ASSERT_TRUE(MoveGripTo(ToastTop(BandMiddle())));
  EXPECT_EQ(State(), GripState::kOpen);
  EXPECT_EQ(Read().hint, "Low enough: close the gripper");
}

TEST_F(GripReadoutTest, BesideTheToastAtTheTableItDoesNotSayClose) {
  // 15 cm from the toast, as low as the teleop goes: closing here catches nothing.
  ASSERT_TRUE(MoveGripTo(ToastTop(0.005) + Eigen::Vector3d(0.0, -0.15, 0.0)));
  const ui::GripReadout r = Read();
  EXPECT_EQ(r.state, "Gripper open");
  EXPECT_EQ(r.hint, "") << "at the table beside the toast";
}

TEST_F(GripReadoutTest, OffTheJawsAxisItSaysByHowMuch) {
  // Along the jaw's closing axis (the table's y with the wrist at home) by 2 cm, at grasp height.
  ASSERT_TRUE(MoveGripTo(ToastTop(BandMiddle()) + Eigen::Vector3d(0.0, 0.02, 0.0)));
  const ui::GripView g = GripViewOf(*world_);
  ASSERT_TRUE(g.alignment_known);
  ASSERT_GT(g.off_axis_m, g.off_axis_window_m);
  const ui::GripReadout r = Read();
  EXPECT_NE(r.hint.find("off the jaw's axis (cyan)"), std::string::npos) << r.hint;
  // Closed there, the grasp catches nothing, and the readout says why.
  Hold(1.5, true);
  ASSERT_EQ(State(), GripState::kClosedOnNothing);
  const ui::GripReadout missed = Read();
  EXPECT_EQ(missed.state.rfind("Closed on nothing", 0), 0u) << missed.state;
  EXPECT_NE(missed.hint.find("It closed"), std::string::npos) << missed.hint;
}

TEST_F(GripReadoutTest, HoldingThenCarryingItStopsGivingGraspHeights) {
  ASSERT_TRUE(MoveGripTo(ToastTop(BandMiddle())));
  Hold(1.5, true);
  ASSERT_EQ(State(), GripState::kHolding);
  ASSERT_TRUE(MoveGripTo(ToastTop(0.10), true));
  ASSERT_EQ(State(), GripState::kHolding);
  const ui::GripReadout r = Read();
  EXPECT_EQ(r.state, "Holding the toast");
  EXPECT_NE(r.height.find(", carrying the toast"), std::string::npos) << r.height;
  EXPECT_EQ(r.height.find("grasps"), std::string::npos) << r.height;
  EXPECT_EQ(r.hint, "");
}

TEST_F(GripReadoutTest, ClosingHighAboveTheToastThenClosedOnNothingNoHeightHint) {
  ASSERT_TRUE(MoveGripTo(ToastTop(0.12)));
  Hold(0.1, true);  // the fingers take longer to close on air than on the toast
  ASSERT_EQ(State(), GripState::kClosing);
  EXPECT_EQ(Read().state, "Closing...");
  EXPECT_EQ(Read().hint, "");
  Hold(1.5, true);
  ASSERT_EQ(State(), GripState::kClosedOnNothing);
  const ui::GripReadout r = Read();
  EXPECT_EQ(r.state.rfind("Closed on nothing", 0), 0u) << r.state;
  EXPECT_EQ(r.hint, "");
}

// Bad input: the wrist turned past its limit. However long the key is held, the wrist stops at
// the limit, and the readout says so and names what turns it back, for the keys and the pad.
TEST_F(GripReadoutTest, TheWristHeldPastItsLimitStopsThereAndTheReadoutSaysHowToTurnItBack) {
  EXPECT_EQ(Read().wrist, "Wrist turned 0\xc2\xb0 (Home / End, up to 90\xc2\xb0 either way)");
  EXPECT_EQ(Read(ui::TeleopMode::kScripted).wrist, "") << "the scripted teacher turns it itself";
  for (const int sign : {1, -1}) {
    teach::TeleopCommand command;
    command.wrist_turn_rad_s = sign * teach::kWristTurnSpeed_rad_s;
    for (int i = 0; i < 100; ++i) world_->Step(teach::CartesianTeleopAction(*world_, command));
    const ui::GripView g = GripViewOf(*world_);
    EXPECT_LE(std::abs(g.wrist_turn_deg), g.wrist_limit_deg + 1.0f) << "held 10 s past the limit";
    EXPECT_GE(std::abs(g.wrist_turn_deg), g.wrist_limit_deg - 0.5f);
    const ui::GripReadout keys = Read();
    EXPECT_EQ(keys.wrist_status, ui::Status::kWarning);
    EXPECT_EQ(keys.wrist, std::string("Wrist at its 90\xc2\xb0 limit: turn back with ") +
                              (sign > 0 ? "End" : "Home"));
    const ui::GripReadout pad = Read(ui::TeleopMode::kGamepad);
    EXPECT_EQ(pad.wrist, std::string("Wrist at its 90\xc2\xb0 limit: push the right stick ") +
                             (sign > 0 ? "right" : "left"));
  }
  // Turned back from the limit, the warning goes.
  teach::TeleopCommand back;
  back.wrist_turn_rad_s = teach::kWristTurnSpeed_rad_s;
  for (int i = 0; i < 5; ++i) world_->Step(teach::CartesianTeleopAction(*world_, back));
  EXPECT_EQ(Read().wrist_status, ui::Status::kOff);
  EXPECT_EQ(Read().wrist.rfind("Wrist turned -", 0), 0u) << Read().wrist;
}

}  // namespace
}  // namespace recon::studio
