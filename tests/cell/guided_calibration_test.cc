// The Calibrate step on a real cell, paced by the teacher: GuidedCalibration fed with frames of
// the digital twin's scene (the real renderer, the real tag detector) and beacon readings through
// a hidden UWB frame, on a simulated clock: a place is taken only once the tag held still and the
// beacon reported from there, a place too near an earlier one, a tag out of view and a silent
// beacon are said and never end the run, and the fit recovers the hidden frame.

#include "devices/cell/guided_calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>

#include "devices/cell/twin_scene.h"
#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/core/rng.h"

namespace recon::cell {
namespace {

using ::testing::HasSubstr;

constexpr int kGuidedWidth = 1280, kGuidedHeight = 960;
constexpr double kStep_s = 0.05;  // the test's clock advances 50 ms per pass, one reading each

class GuidedCalibrationTest : public ::testing::Test {
 protected:
  GuidedCalibrationTest() : renderer_(render::MujocoRendererFactory()()) {
    layout_.bowl = {0.12, 0.0};  // clear of the beacon's places
    scene_.Arrange(layout_);
    options_.points = 5;
    options_.beacon = "plate";
    options_.beacon_tag = {scene_.BeaconTagSize(), scene_.BeaconTagHeight()};
  }

  /// The teacher puts the plate (and the beacon beside it) at table (x, y).
  void PutPlate(double x, double y) {
    layout_.plate = {x, y};
    scene_.Arrange(layout_);
    frame_ = renderer_->Render(scene_.scene(), "top", kGuidedWidth, kGuidedHeight);
  }

  /// Passes of `seconds`, each with the frame and (unless `silent`) one reading of the beacon
  /// where it stands, through the hidden frame with +-1 cm of noise.
  void Run(GuidedCalibration& calibration, double seconds, bool silent = false,
           const RgbImage* frame = nullptr) {
    for (double t = 0; t < seconds - 1e-9; t += kStep_s) {
      std::vector<devices::BeaconSample> samples;
      if (!silent) {
        devices::BeaconSample sample;
        sample.beacon = "plate";
        sample.position_uwb_m =
            hidden_.Apply(scene_.BeaconPosition()) +
            Eigen::Vector3d(noise_.Uniform(-0.01, 0.01), noise_.Uniform(-0.01, 0.01), 0.0);
        samples.push_back(sample);
      }
      now_s_ += kStep_s;
      calibration.Update(frame != nullptr ? frame : &frame_, samples, now_s_);
    }
  }

  GuidedCalibration Make() {
    return GuidedCalibration(scene_.TopCamera(kGuidedWidth, kGuidedHeight), options_);
  }

  TwinScene scene_;
  std::unique_ptr<worlds::SceneRenderer> renderer_;
  TwinLayout layout_;
  RgbImage frame_;
  GuidedCalibrationOptions options_;
  // The installation's UWB frame: anchors 2 m off and turned 30 degrees.
  const calib::RigidTransform hidden_{Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()).matrix(),
                                      Eigen::Vector3d(2.0, -1.0, 0.3)};
  Rng noise_{29};  // seed 29: the readings' noise
  double now_s_ = 0;
};

TEST_F(GuidedCalibrationTest, TakesEachPlaceOnceTheTagHeldStillAndRecoversTheHiddenFrame) {
  GuidedCalibration calibration = Make();
  EXPECT_THAT(calibration.status().prompt, HasSubstr("Place 1 of 5: put the beacon"));
  const std::vector<Eigen::Vector2d> places = {
      {0.35, -0.3}, {0.75, -0.25}, {0.7, 0.2}, {0.4, 0.15}, {0.55, -0.05}};
  std::vector<Eigen::Vector3d> truth;
  for (size_t i = 0; i < places.size(); ++i) {
    PutPlate(places[i].x(), places[i].y());
    truth.push_back(scene_.BeaconPosition());
    // Not before the tag has held still for steady_s (1 s)...
    Run(calibration, 0.9);
    EXPECT_EQ(calibration.status().taken, static_cast<int>(i)) << "place " << i;
    EXPECT_TRUE(calibration.status().tag_seen);
    EXPECT_THAT(calibration.status().prompt, HasSubstr("hold still"));
    EXPECT_GT(calibration.status().held_fraction, 0.5);
    // ...and then within a look (look_period_s, 0.2 s) of it.
    Run(calibration, 0.5);
    EXPECT_EQ(calibration.status().taken, static_cast<int>(i + 1)) << "place " << i;
  }
  ASSERT_TRUE(calibration.Done());
  EXPECT_THAT(calibration.status().prompt, HasSubstr("All 5 places taken"));
  for (size_t i = 0; i < places.size(); ++i) {
    const CollectedPose& pose = calibration.poses()[i];
    EXPECT_LT((pose.point.tag_m - truth[i]).head<2>().norm(), 0.01) << "place " << i;
    EXPECT_LT((pose.point.uwb_m - hidden_.Apply(truth[i])).head<2>().norm(), 0.01);
    EXPECT_GE(pose.uwb_samples, options_.min_uwb_samples);
    EXPECT_LT(pose.tag_spread_m, options_.steady_tolerance_m);
  }
  const calib::CalibrationReport report = calibration.Fit();
  EXPECT_TRUE(report.passed) << report.Summary();
  EXPECT_LT(report.rmse_m, 0.02);
  for (const Eigen::Vector3d& p : truth) {
    EXPECT_LT((report.transform.Apply(hidden_.Apply(p)) - p).head<2>().norm(), 0.02);
  }
}

TEST_F(GuidedCalibrationTest, APlaceTooNearAnUnseenTagAndASilentBeaconAreSaidAndTheRunGoesOn) {
  GuidedCalibration calibration = Make();
  PutPlate(0.4, -0.2);
  Run(calibration, 1.5);
  ASSERT_EQ(calibration.status().taken, 1);
  // Left where it was taken, or moved only 5 cm: not a new place, however long it stands.
  Run(calibration, 3.0);
  EXPECT_EQ(calibration.status().taken, 1);
  EXPECT_THAT(calibration.status().prompt,
              HasSubstr("Place 2 of 5: this is within 8 cm of place 1: move the beacon"));
  PutPlate(0.45, -0.2);
  Run(calibration, 3.0);
  EXPECT_EQ(calibration.status().taken, 1);

  // The camera loses the tag (a hand over it: here, a blank frame): said, nothing taken.
  const RgbImage blank{kGuidedWidth, kGuidedHeight,
                       std::vector<uint8_t>(kGuidedWidth * kGuidedHeight * 3, 128)};
  PutPlate(0.7, 0.1);
  Run(calibration, 2.0, false, &blank);
  EXPECT_EQ(calibration.status().taken, 1);
  EXPECT_FALSE(calibration.status().tag_seen);
  EXPECT_THAT(calibration.status().prompt, HasSubstr("does not see the beacon's tag (id 10)"));

  // The beacon goes silent while the tag holds still: said after 2 s, nothing taken...
  Run(calibration, 3.0, true);
  EXPECT_EQ(calibration.status().taken, 1);
  EXPECT_TRUE(calibration.status().beacon_silent);
  EXPECT_THAT(calibration.status().prompt, HasSubstr("No reading from the beacon for 3 s"));
  // ...and when it reports again, the place is taken from its new readings.
  Run(calibration, 0.5);
  EXPECT_FALSE(calibration.status().beacon_silent);
  EXPECT_EQ(calibration.status().taken, 2);
  EXPECT_LT((calibration.poses()[1].point.uwb_m - hidden_.Apply(scene_.BeaconPosition()))
                .head<2>()
                .norm(),
            0.01);
}

TEST_F(GuidedCalibrationTest, ReadingsFromTheWayThereAreNotAveragedIntoAPlace) {
  GuidedCalibration calibration = Make();
  PutPlate(0.4, -0.2);
  const Eigen::Vector3d old_place = hidden_.Apply(scene_.BeaconPosition());
  Run(calibration, 1.5);
  PutPlate(0.7, 0.15);
  const Eigen::Vector3d new_tag = scene_.BeaconPosition();
  // Readings still come from the old place (a slow serial line) until the camera has seen the
  // tag settle at the new one, and for 0.15 s after: within settle_s (0.2 s), not this place's.
  const auto late_reading = [&] {
    devices::BeaconSample late;
    late.beacon = "plate";
    late.position_uwb_m = old_place;
    now_s_ += kStep_s;
    calibration.Update(&frame_, {late}, now_s_);
  };
  for (int i = 0; i < 20 && (calibration.status().tag_table_m - new_tag).head<2>().norm() > 0.01;
       ++i) {
    late_reading();
  }
  ASSERT_LT((calibration.status().tag_table_m - new_tag).head<2>().norm(), 0.01);
  for (int i = 0; i < 3; ++i) late_reading();
  Run(calibration, 1.5);
  ASSERT_EQ(calibration.status().taken, 2);
  EXPECT_LT((calibration.poses()[1].point.uwb_m - hidden_.Apply(scene_.BeaconPosition()))
                .head<2>()
                .norm(),
            0.01);
}

TEST_F(GuidedCalibrationTest, OtherBeaconsReadingsAndBadOptionsAreRefused) {
  options_.points = 2;
  EXPECT_THROW(Make(), UserError);
  options_.points = 5;
  options_.steady_s = 0;
  EXPECT_THROW(Make(), UserError);
  options_.steady_s = 1.0;
  GuidedCalibration calibration = Make();
  PutPlate(0.4, -0.2);
  for (int i = 0; i < 40; ++i) {  // 2 s of readings of another beacon only
    devices::BeaconSample other;
    other.beacon = "bowl";
    other.position_uwb_m = hidden_.Apply(scene_.BeaconPosition());
    now_s_ += kStep_s;
    calibration.Update(&frame_, {other}, now_s_);
  }
  EXPECT_EQ(calibration.status().taken, 0);
  EXPECT_FALSE(calibration.status().beacon_uwb_m.has_value());
}

}  // namespace
}  // namespace recon::cell
