#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "devices/camera/image_file.h"
#include "devices/uwb/fake_dwm1001.h"
#include "engine/core/image.h"

namespace recon::cell::testing {

// The fakes a real-cell test sets up, shared by the device layer's and the studio's tests.

/// A DWM1001 tag (FakeDwm1001 on a pseudo-terminal) that stands still at `position_uwb_m`,
/// reporting it with quality 90 every `period_ms`.
inline std::unique_ptr<uwb::FakeDwm1001> StillBeacon(uint64_t node_id,
                                                     const Eigen::Vector3d& position_uwb_m,
                                                     int period_ms = 20) {
  uwb::FakeDwm1001::Options options;
  options.period_ms = period_ms;
  options.node_id = node_id;
  options.next_reading = [position_uwb_m] {
    uwb::UwbReading r;
    r.has_position = true;
    r.x_m = position_uwb_m.x();
    r.y_m = position_uwb_m.y();
    r.z_m = position_uwb_m.z();
    r.quality = 90;
    return r;
  };
  return std::make_unique<uwb::FakeDwm1001>(options);
}

/// A folder of `count` copies of `image` (frame_000.png, ...), for an image-sequence camera.
inline void WriteFrameFolder(const std::filesystem::path& folder, const RgbImage& image,
                             int count = 3) {
  std::filesystem::create_directories(folder);
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03d.png", i);
    camera::WriteImage((folder / name).string(), image);
  }
}

}  // namespace recon::cell::testing
