#include "devices/cell/calibration_collector.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "engine/core/error.h"

namespace recon::cell {

std::optional<tags::TagLocation> LocateTag(tags::TagDetector& detector,
                                           const tags::TableLocator& locator, const RgbImage& frame,
                                           int tag_id) {
  for (const tags::TagDetection& detection : detector.Detect(frame)) {
    if (detection.id == tag_id) return locator.Locate(detection);
  }
  return std::nullopt;
}

CollectedPose PoseFromHold(const std::vector<Eigen::Vector3d>& truth_m,
                           const std::vector<Eigen::Vector3d>& uwb_m) {
  const auto mean = [](const std::vector<Eigen::Vector3d>& points) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points) sum += p;
    return Eigen::Vector3d(sum / static_cast<double>(points.size()));
  };
  CollectedPose pose;
  pose.point.tag_m = mean(truth_m);
  pose.point.uwb_m = mean(uwb_m);
  pose.frames_with_tag = pose.frames_tried = static_cast<int>(truth_m.size());
  pose.uwb_samples = static_cast<int>(uwb_m.size());
  for (const Eigen::Vector3d& p : truth_m) {
    pose.tag_spread_m = std::max(pose.tag_spread_m, (p - pose.point.tag_m).norm());
  }
  return pose;
}

CollectedPose CollectPose(devices::Camera& camera, devices::BeaconSource& beacons,
                          const tags::TableLocator& locator, const devices::Clock& clock,
                          const PoseCollectOptions& options, const std::string& pose_label) {
  if (options.frames < 1 || options.max_frames < options.frames || options.uwb_samples < 1) {
    throw UserError(
        "calibration: frames, max_frames and uwb_samples must be positive, with "
        "max_frames >= frames");
  }
  beacons.Poll();  // what arrived while the teacher was moving the beacon is not this pose

  CollectedPose pose;
  tags::TagDetector detector;
  std::vector<Eigen::Vector3d> tag_positions;
  while (static_cast<int>(tag_positions.size()) < options.frames &&
         pose.frames_tried < options.max_frames) {
    const devices::CameraFrame frame = camera.Capture();
    ++pose.frames_tried;
    if (auto located = LocateTag(detector, locator, frame.image, options.beacon_tag_id)) {
      tag_positions.push_back(located->position_table_m);
    }
  }
  pose.frames_with_tag = static_cast<int>(tag_positions.size());
  if (tag_positions.empty()) {
    throw UserError(pose_label + ": " + camera.Describe() + " did not see the beacon's tag " +
                    std::to_string(options.beacon_tag_id) + " in " +
                    std::to_string(pose.frames_tried) +
                    " frames; is the tag face up, unobstructed and in the picture?");
  }
  Eigen::Vector3d tag_mean = Eigen::Vector3d::Zero();
  for (const auto& p : tag_positions) tag_mean += p;
  tag_mean /= static_cast<double>(tag_positions.size());
  for (const auto& p : tag_positions) {
    pose.tag_spread_m = std::max(pose.tag_spread_m, (p - tag_mean).norm());
  }

  Eigen::Vector3d uwb_sum = Eigen::Vector3d::Zero();
  const double deadline = clock.NowSeconds() + options.uwb_timeout_s;
  while (pose.uwb_samples < options.uwb_samples) {
    for (const devices::BeaconSample& sample : beacons.Poll()) {
      if (!options.beacon.empty() && sample.beacon != options.beacon) continue;
      if (!sample.position_uwb_m.allFinite()) continue;
      uwb_sum += sample.position_uwb_m;
      if (++pose.uwb_samples == options.uwb_samples) break;
    }
    if (pose.uwb_samples >= options.uwb_samples) break;
    if (clock.NowSeconds() > deadline) {
      throw UserError(pose_label + ": " + beacons.Describe() + " gave " +
                      std::to_string(pose.uwb_samples) + " of " +
                      std::to_string(options.uwb_samples) + " positions" +
                      (options.beacon.empty() ? "" : " of beacon '" + options.beacon + "'") +
                      " in " + std::to_string(options.uwb_timeout_s) +
                      " s; is the beacon powered and within range of the anchors?");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  pose.point.tag_m = tag_mean;
  pose.point.uwb_m = uwb_sum / pose.uwb_samples;
  return pose;
}

}  // namespace recon::cell
