#include "devices/camera/image_sequence_camera.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "devices/camera/image_file.h"
#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::camera {

namespace {

bool IsImageFile(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

}  // namespace

ImageSequenceCamera::ImageSequenceCamera(const std::string& folder, ImageSequenceOptions options)
    : folder_(folder), options_(std::move(options)) {
  if (!(options_.fps > 0.0)) throw UserError("the image sequence's fps must be positive");
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw UserError("cannot open the image sequence " + folder + ": not a folder");
  }
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (entry.is_regular_file() && IsImageFile(entry.path())) {
      files_.push_back(entry.path().string());
    }
  }
  if (error) throw UserError("cannot list the image sequence " + folder + ": " + error.message());
  if (files_.empty()) {
    throw UserError("the image sequence " + folder + " holds no .png or .jpg frames");
  }
  std::sort(files_.begin(), files_.end());
  const RgbImage first = Load(files_.front());
  width_ = first.width;
  height_ = first.height;
  if (options_.undistort &&
      (options_.undistort->image_width != width_ || options_.undistort->image_height != height_)) {
    throw UserError("the calibration is for " + std::to_string(options_.undistort->image_width) +
                    "x" + std::to_string(options_.undistort->image_height) +
                    " frames but the image sequence " + folder + " has " + std::to_string(width_) +
                    "x" + std::to_string(height_));
  }
  if (options_.undistort) undistorter_.emplace(*options_.undistort);
}

RgbImage ImageSequenceCamera::Load(const std::string& file) const {
  try {
    return ReadImage(file);
  } catch (const UserError&) {
    throw UserError("cannot read the frame " + file + ": not a readable image");
  }
}

devices::CameraFrame ImageSequenceCamera::Capture() {
  const int64_t count = static_cast<int64_t>(files_.size());
  if (next_ >= count && !options_.loop) {
    throw UserError("the image sequence " + folder_ + " ended after " + std::to_string(count) +
                    " frames");
  }
  const std::string& file = files_[static_cast<size_t>(next_ % count)];
  devices::CameraFrame frame;
  frame.image = Load(file);
  if (frame.image.width != width_ || frame.image.height != height_) {
    throw UserError("the frame " + file + " is " + std::to_string(frame.image.width) + "x" +
                    std::to_string(frame.image.height) + ", the sequence's first frame " +
                    std::to_string(width_) + "x" + std::to_string(height_));
  }
  if (undistorter_) frame.image = undistorter_->Apply(frame.image);
  frame.timestamp_s = static_cast<double>(next_) / options_.fps;
  frame.sequence = next_;
  if (options_.real_time) {
    if (next_ == 0) start_s_ = SteadySeconds();
    const double wait_s = start_s_ + frame.timestamp_s - SteadySeconds();
    if (wait_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
  }
  ++next_;
  return frame;
}

std::string ImageSequenceCamera::Describe() const {
  char fps[32];
  std::snprintf(fps, sizeof(fps), "%.4g", options_.fps);
  std::string text = "image sequence " + folder_ + " (" + std::to_string(files_.size()) +
                     " frames), " + std::to_string(width_) + "x" + std::to_string(height_) +
                     " at " + fps + " fps";
  if (options_.undistort) text += ", undistorted";
  return text;
}

}  // namespace recon::camera
