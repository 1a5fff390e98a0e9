#include "app/cli/camera_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/cli/option_checks.h"
#include "app/cli/output_path.h"
#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/camera_pose.h"
#include "devices/camera/image_file.h"
#include "devices/camera/image_sequence_camera.h"
#include "devices/camera/open_camera.h"
#include "devices/camera/opencv_camera.h"
#include "devices/camera/table_tags_file.h"
#include "devices/tags/tag_detector.h"
#include "engine/core/error.h"

namespace recon::cli {

namespace {

struct CameraFlags {
  std::string device;
  std::string calibration;
  std::string out;
  std::string tags;
  int frames = 30;
  int count = 1;
  int min_tags = 2;
  bool undistort = false;
  bool json = false;
  bool force = false;
};

std::optional<camera::CameraCalibration> LoadCalibration(const CameraFlags& flags) {
  if (flags.calibration.empty()) return std::nullopt;
  return camera::ReadCameraCalibration(flags.calibration);
}

nlohmann::json IntrinsicsJson(const camera::CameraCalibration& c) {
  const tags::CameraIntrinsics k = c.ToIntrinsics();
  return {{"fx", k.fx},
          {"fy", k.fy},
          {"cx", k.cx},
          {"cy", k.cy},
          {"width", k.width},
          {"height", k.height},
          {"distortion", c.distortion}};
}

void CheckCalibrationSize(const camera::CameraCalibration& c, const std::string& path, int width,
                          int height, const std::string& device) {
  if (c.image_width != width || c.image_height != height) {
    throw UserError("the calibration " + path + " is for " + std::to_string(c.image_width) + "x" +
                    std::to_string(c.image_height) + " frames but " + device + " delivers " +
                    std::to_string(width) + "x" + std::to_string(height));
  }
}

void RunInfo(const CameraFlags& flags) {
  const std::optional<camera::CameraCalibration> calibration = LoadCalibration(flags);
  const std::unique_ptr<devices::Camera> cam = camera::OpenCamera(flags.device);
  std::vector<devices::CameraFrame> frames;
  for (int i = 0; i < flags.frames; ++i) frames.push_back(cam->Capture());
  const RgbImage& last = frames.back().image;
  const double span_s = frames.back().timestamp_s - frames.front().timestamp_s;
  const double measured_fps = frames.size() > 1 && span_s > 0 ? (frames.size() - 1) / span_s : 0;
  std::string backend = "image sequence";
  double nominal_fps = 0.0;
  int64_t failed = 0, dropped = 0;
  if (const auto* cv_cam = dynamic_cast<const camera::OpenCvCamera*>(cam.get())) {
    backend = cv_cam->backend();
    nominal_fps = cv_cam->nominal_fps();
    failed = cv_cam->failed_reads();
    dropped = cv_cam->dropped_frames();
  } else if (const auto* seq = dynamic_cast<const camera::ImageSequenceCamera*>(cam.get())) {
    nominal_fps = seq->fps();
  }
  if (calibration) {
    CheckCalibrationSize(*calibration, flags.calibration, last.width, last.height, flags.device);
  }
  if (flags.json) {
    nlohmann::json out = {{"device", flags.device},       {"description", cam->Describe()},
                          {"backend", backend},           {"width", last.width},
                          {"height", last.height},        {"frames", frames.size()},
                          {"measured_fps", measured_fps}, {"nominal_fps", nominal_fps},
                          {"failed_reads", failed},       {"dropped_frames", dropped}};
    if (calibration) out["intrinsics"] = IntrinsicsJson(*calibration);
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("camera:   %s\n", cam->Describe().c_str());
  std::printf("backend:  %s\n", backend.c_str());
  std::printf("size:     %dx%d\n", last.width, last.height);
  std::printf(
      "frames:   %zu grabbed in %.3f s: %.2f fps measured (%.4g nominal), %lld failed "
      "reads, %lld dropped\n",
      frames.size(), span_s, measured_fps, nominal_fps, static_cast<long long>(failed),
      static_cast<long long>(dropped));
  if (calibration) {
    const tags::CameraIntrinsics k = calibration->ToIntrinsics();
    std::printf("intrinsics (%s; pixel centres at +0.5): fx %.3f fy %.3f cx %.3f cy %.3f\n",
                flags.calibration.c_str(), k.fx, k.fy, k.cx, k.cy);
    std::string d;
    for (double v : calibration->distortion) d += " " + std::to_string(v);
    std::printf("distortion (OpenCV order k1 k2 p1 p2 k3 ...):%s\n", d.c_str());
  }
}

// frame.png for one frame; frame_0000.png, frame_0001.png, ... for several.
std::string FramePath(const std::string& out, int index, int count) {
  if (count == 1) return out;
  const std::filesystem::path path(out);
  char suffix[16];
  std::snprintf(suffix, sizeof(suffix), "_%04d", index);
  return (path.parent_path() / (path.stem().string() + suffix + path.extension().string()))
      .string();
}

void RunGrab(const CameraFlags& flags) {
  if (flags.undistort && flags.calibration.empty()) {
    throw UserError("--undistort needs --calibration FILE");
  }
  camera::OpenCameraOptions options;
  if (flags.undistort) options.undistort = LoadCalibration(flags);
  for (int i = 0; i < flags.count; ++i) {
    CheckOutputFile("--out", FramePath(flags.out, i, flags.count), flags.force);
  }
  const std::unique_ptr<devices::Camera> cam = camera::OpenCamera(flags.device, options);
  for (int i = 0; i < flags.count; ++i) {
    const devices::CameraFrame frame = cam->Capture();
    const std::string path = FramePath(flags.out, i, flags.count);
    camera::WriteImage(path, frame.image);
    std::printf("wrote %s (%dx%d, frame %lld at %.3f s)\n", path.c_str(), frame.image.width,
                frame.image.height, static_cast<long long>(frame.sequence), frame.timestamp_s);
  }
}

void RunPose(const CameraFlags& flags) {
  const std::vector<camera::TableTag> table_tags = camera::ReadTableTags(flags.tags);
  camera::OpenCameraOptions options;
  options.undistort = LoadCalibration(flags);
  const std::unique_ptr<devices::Camera> cam = camera::OpenCamera(flags.device, options);
  const devices::CameraFrame frame = cam->Capture();
  tags::TagDetector detector;
  const camera::CameraPoseEstimate estimate = camera::EstimateCameraPose(
      options.undistort->ToIntrinsics(), table_tags, detector.Detect(frame.image), flags.min_tags);
  const Eigen::Vector3d& p = estimate.camera.position_table_m();
  const Eigen::Vector3d forward = estimate.camera.table_R_cv().col(2);
  const double down_tilt_deg = std::asin(std::clamp(-forward.z(), -1.0, 1.0)) * 180.0 / M_PI;
  if (flags.json) {
    const Eigen::Matrix3d& r = estimate.camera.table_R_cv();
    nlohmann::json out = {
        {"device", flags.device},
        {"position_table_m", {p.x(), p.y(), p.z()}},
        {"table_R_cv",
         {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}}},
        {"reprojection_rms_px", estimate.reprojection_rms_px},
        {"reprojection_max_px", estimate.reprojection_max_px},
        {"used_ids", estimate.used_ids},
        {"missing_ids", estimate.missing_ids},
        {"unknown_ids", estimate.unknown_ids}};
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("camera position in the table frame: x %.4f y %.4f z %.4f m\n", p.x(), p.y(), p.z());
  std::printf("looking along (%.3f, %.3f, %.3f), %.1f deg below horizontal\n", forward.x(),
              forward.y(), forward.z(), down_tilt_deg);
  std::printf("reprojection error: %.3f px RMS, %.3f px max over %zu tags\n",
              estimate.reprojection_rms_px, estimate.reprojection_max_px, estimate.used_ids.size());
  if (!estimate.missing_ids.empty()) {
    std::printf("not seen: %zu of the table tags\n", estimate.missing_ids.size());
  }
}

}  // namespace

void AddCameraCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("camera", "cameras: V4L2 devices, video files, image folders");
  cmd->require_subcommand(1);
  cmd->preparse_callback([](size_t) { camera::SilenceOpenCvLogging(); });
  auto flags = std::make_shared<CameraFlags>();
  const std::string device_help =
      "/dev/videoN, a V4L2 index, a video file, or a folder of PNG/JPG frames";

  CLI::App* info = cmd->add_subcommand("info", "open a camera, grab frames, print what it is");
  info->add_option("--device", flags->device, device_help)->required();
  info->add_option("--calibration", flags->calibration, "OpenCV calibration YAML to show");
  info->add_option("--frames", flags->frames, "frames to grab for the rate measurement")
      ->capture_default_str()
      ->check(WholeBetween(1, 100000));
  info->add_flag("--json", flags->json, "print one JSON object");
  info->callback([flags] { RunInfo(*flags); });

  CLI::App* grab = cmd->add_subcommand("grab", "save frames as images");
  grab->add_option("--device", flags->device, device_help)->required();
  grab->add_option("--out", flags->out, "image to write (.png or .jpg); several get _0000, ...")
      ->required();
  AddForceFlag(*grab, flags->force);
  grab->add_option("--count", flags->count, "frames to save")
      ->capture_default_str()
      ->check(WholeBetween(1, 100000));
  grab->add_flag("--undistort", flags->undistort, "remove lens distortion (needs --calibration)");
  grab->add_option("--calibration", flags->calibration, "OpenCV calibration YAML");
  grab->callback([flags] { RunGrab(*flags); });

  CLI::App* pose = cmd->add_subcommand("pose", "the camera's pose in the table frame from tags");
  pose->add_option("--device", flags->device, device_help)->required();
  pose->add_option("--calibration", flags->calibration, "OpenCV calibration YAML")->required();
  pose->add_option("--tags", flags->tags, "table tags JSON (ids, centres, sizes)")->required();
  pose->add_option("--min-tags", flags->min_tags, "fewest table tags to accept")
      ->capture_default_str()
      ->check(WholeBetween(1, 1000));
  pose->add_flag("--json", flags->json, "print one JSON object");
  pose->callback([flags] { RunPose(*flags); });
}

}  // namespace recon::cli
