#include "devices/cell/guided_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "engine/core/error.h"

namespace recon::cell {

namespace {

std::string Format(const char* format, double a, double b = 0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

}  // namespace

GuidedCalibration::GuidedCalibration(const tags::PinholeCamera& camera,
                                     GuidedCalibrationOptions options)
    : options_(std::move(options)),
      locator_(camera, options_.beacon_tag),
      detector_(std::make_unique<tags::TagDetector>()) {
  if (options_.points < 3) throw UserError("a calibration needs at least 3 places for a rigid fit");
  for (double v : {options_.steady_s, options_.steady_tolerance_m, options_.min_separation_m,
                   options_.beacon_silent_s, options_.look_period_s}) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw UserError("guided calibration: times and distances must be positive");
    }
  }
  if (options_.min_uwb_samples < 1) {
    throw UserError("guided calibration: at least one beacon reading per place");
  }
  locator_.SetTagSpec(options_.beacon_tag_id, options_.beacon_tag);
  status_.total = options_.points;
  last_reading_s_ = -1e9;
  Prompt(0.0);
}

void GuidedCalibration::Update(const RgbImage* frame,
                               const std::vector<devices::BeaconSample>& samples, double now_s) {
  if (Done()) return;
  if (!looked_) last_reading_s_ = now_s;  // silence is counted from the start
  for (const devices::BeaconSample& sample : samples) {
    if (!options_.beacon.empty() && sample.beacon != options_.beacon) continue;
    status_.beacon_uwb_m = sample.position_uwb_m;
    last_reading_s_ = now_s;
    // Readings are stamped here, as they reach the studio, so the settle time also covers
    // the serial line's and the hub's latency.
    if (anchor_ && now_s >= hold_start_s_ + options_.settle_s) {
      hold_uwb_.push_back(sample.position_uwb_m);
    }
  }
  if (frame != nullptr && now_s - last_look_s_ >= options_.look_period_s) Look(*frame, now_s);
  status_.held_fraction = 0;
  if (anchor_ && too_near_pose_ < 0) {
    status_.held_fraction = std::min(1.0, (now_s - hold_start_s_) / options_.steady_s);
    if (status_.held_fraction >= 1.0 &&
        static_cast<int>(hold_uwb_.size()) >= options_.min_uwb_samples) {
      TakePose();
    }
  }
  status_.beacon_silent = now_s - last_reading_s_ > options_.beacon_silent_s;
  Prompt(now_s);
}

void GuidedCalibration::Look(const RgbImage& frame, double now_s) {
  last_look_s_ = now_s;
  looked_ = true;
  std::optional<tags::TagLocation> located;
  for (const tags::TagDetection& detection : detector_->Detect(frame)) {
    if (detection.id != options_.beacon_tag_id) continue;
    located = locator_.Locate(detection);
    status_.tag_pixel = {static_cast<float>(detection.center_px.x()),
                         static_cast<float>(detection.center_px.y())};
    break;
  }
  status_.tag_seen = located.has_value();
  if (!located) {
    anchor_.reset();
    return;
  }
  const Eigen::Vector3d p = located->position_table_m;
  status_.tag_table_m = p;
  if (!anchor_ || (p - *anchor_).head<2>().norm() > options_.steady_tolerance_m) {
    // The beacon moved (or was just put down): the hold starts again from here.
    anchor_ = p;
    hold_start_s_ = now_s;
    hold_tags_.clear();
    hold_uwb_.clear();
    too_near_pose_ = -1;
    for (size_t i = 0; i < poses_.size(); ++i) {
      if ((poses_[i].point.tag_m - p).head<2>().norm() < options_.min_separation_m) {
        too_near_pose_ = static_cast<int>(i);
      }
    }
  }
  hold_tags_.push_back(p);
}

void GuidedCalibration::TakePose() {
  poses_.push_back(PoseFromHold(hold_tags_, hold_uwb_));
  status_.taken = static_cast<int>(poses_.size());
  // The beacon still stands where it was taken: the next look finds it too near this place.
  anchor_.reset();
  hold_tags_.clear();
  hold_uwb_.clear();
}

void GuidedCalibration::Prompt(double now_s) {
  const int place = status_.taken + 1;
  const std::string of =
      "Place " + std::to_string(place) + " of " + std::to_string(options_.points) + ": ";
  std::string& prompt = status_.prompt;
  if (Done()) {
    prompt = "All " + std::to_string(options_.points) + " places taken.";
  } else if (status_.beacon_silent) {
    prompt = Format(
        "No reading from the beacon for %.0f s: check that it is switched on and its port "
        "plugged in. The calibration goes on when it reports again.",
        now_s - last_reading_s_);
  } else if (!looked_) {
    prompt = of + "put the beacon on the table, its tag up, and let go.";
  } else if (!status_.tag_seen) {
    prompt = of + "the camera does not see the beacon's tag (id " +
             std::to_string(options_.beacon_tag_id) +
             "): put it on the table, tag up, where the camera sees it.";
  } else if (too_near_pose_ >= 0) {
    prompt = of + "this is within " + Format("%.0f", 100 * options_.min_separation_m) +
             " cm of place " + std::to_string(too_near_pose_ + 1) +
             ": move the beacon somewhere new.";
  } else if (status_.held_fraction < 1.0) {
    prompt = of + "hold still...";
  } else {
    prompt = of + "waiting for the beacon's readings from here.";
  }
}

calib::CalibrationReport GuidedCalibration::Fit() const {
  std::vector<calib::CalibrationPoint> points;
  for (const CollectedPose& pose : poses_) points.push_back(pose.point);
  return calib::Calibrate(points, options_.calibration);
}

}  // namespace recon::cell
