#pragma once

#include <cstdint>
#include <string>

#include "engine/core/image.h"

namespace recon::devices {

/// One image from a camera, stamped when it was taken.
struct CameraFrame {
  RgbImage image;
  double timestamp_s = 0.0;
  int64_t sequence = 0;  ///< 0, 1, 2, ... per camera; a gap means frames were lost
};

/// A camera as the teaching workflow sees it: the simulated top-down camera (an offscreen MuJoCo
/// render) or a real one. Capture may block until the next frame; it throws UserError when the
/// device is gone (unplugged, closed), naming it.
class Camera {
 public:
  virtual ~Camera() = default;
  virtual CameraFrame Capture() = 0;
  /// Short human-readable identity, e.g. "simulated top camera 64x64".
  virtual std::string Describe() const = 0;
};

}  // namespace recon::devices
