#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/calib/calibration.h"

namespace recon::cli {

/// What `recon calibrate` needs for a calibration with real devices.
struct DeviceCalibrateFlags {
  std::string camera;              ///< /dev/videoN, an index, a video file or a folder of frames
  std::string camera_calibration;  ///< OpenCV calibration YAML of that camera
  std::string table_tags;          ///< JSON: the table tags' ids, places and sizes
  std::vector<std::string> beacon_ports;
  std::string beacon;              ///< which beacon carries the tag ("plate"); empty: any
  std::vector<std::string> names;  ///< NODE_ID=name, repeatable
  std::string mode = "lec";        ///< lec or tlv
  int beacon_tag_id = 10;
  double beacon_tag_size_m = 0.0352;
  double beacon_tag_height_m = 0.06;
  int frames = 5;
  int uwb_samples = 10;
  bool no_wait = false;  ///< do not wait for Enter between poses (for scripted runs)
};

/// Runs the calibration with a real camera and DWM1001 beacons: the teacher puts the beacon at
/// each pose and presses Enter; prints the camera's pose, each pose's evidence and the fit.
calib::CalibrationReport RunDeviceCalibrate(const DeviceCalibrateFlags& flags, int points,
                                            const calib::CalibrationOptions& options);

}  // namespace recon::cli
