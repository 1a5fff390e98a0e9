#pragma once

#include <CLI/CLI.hpp>

namespace recon::cli {

/// Adds `recon camera`:
///   info --device D [--calibration Y] [--frames N] [--json]: opens the camera, grabs N frames
///     (30) and prints its size, measured frame rate, backend and, with a calibration, its
///     intrinsics;
///   grab --device D --out frame.png [--count N] [--undistort --calibration Y]: saves frames;
///   pose --device D --calibration Y --tags table_tags.json [--min-tags K] [--json]: the
///     camera's pose in the table frame from tags at known places (devices/camera/camera_pose.h).
/// D is /dev/videoN, a V4L2 index, a video file or a folder of PNG/JPG frames. Errors exit 2
/// naming the device or file.
void AddCameraCommand(CLI::App& app);

}  // namespace recon::cli
