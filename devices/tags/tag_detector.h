#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "engine/core/image.h"

// libapriltag's types, kept out of this header so its C macros and flexible-array structs stay in
// the .cc files.
struct apriltag_detector;
struct apriltag_family;

namespace recon::tags {

/// Pixel coordinates here follow libapriltag: (col, row) = (x, y), x right, y down, measured so
/// that pixel (c, r) has its centre at (c + 0.5, r + 0.5), i.e. the image spans [0, width] x
/// [0, height] (the OpenGL window convention). On the tags tests' synthetic images the mean
/// corner offset is below 0.001 px (the other convention would show 0.5), and
/// CameraIntrinsics::FromFovy relies on it.
struct TagDetection {
  int id = -1;
  int hamming = 0;               ///< bits corrected; 0 is a clean read
  double decision_margin = 0.0;  ///< mean contrast of the data bits; higher is more certain
  Eigen::Vector2d center_px;     ///< the tag centre projected through the homography
  /// Corners of the black border's outer edge, counter-clockwise around the tag as seen in the
  /// image, starting at the tag's bottom-left (libapriltag's order).
  std::array<Eigen::Vector2d, 4> corners_px;
  /// Row-major 3x3 homography from tag coordinates (-1..1, the black border's outer edge) to
  /// pixels; kept because pose estimation (TableLocator) needs it.
  std::array<double, 9> homography{};
};

/// Detector settings; the defaults favour accuracy on a 640 x 480 frame over speed.
struct TagDetectorOptions {
  /// Quad detection on an image shrunk by this factor: faster, but small tags are lost and
  /// corners are less precise. 1 = full resolution.
  double quad_decimate = 1.0;
  /// Gaussian blur applied before quad detection (0 = none); useful only for noisy images.
  double quad_sigma = 0.0;
  int nthreads = 1;
  /// Snap quad edges to the strongest nearby gradient, undoing decimation's loss of corner
  /// precision. libapriltag 3.3 ignores it when quad_decimate is 1.
  bool refine_edges = true;
  /// Most bit errors accepted when decoding (libapriltag allows up to 3 for tag36h11, but every
  /// extra bit raises the chance of reading a wrong id).
  int max_hamming = 2;
};

/// Detects tag36h11 markers in RGB images. Owns a libapriltag detector and family and frees
/// both (and every detection) itself. Not thread-safe: use one per thread.
class TagDetector {
 public:
  /// Throws UserError for options out of range (decimate < 1, nthreads < 1, max_hamming
  /// outside 0..3).
  explicit TagDetector(TagDetectorOptions options = {});
  ~TagDetector();

  TagDetector(const TagDetector&) = delete;
  TagDetector& operator=(const TagDetector&) = delete;

  /// The tags found in `image` (rows top to bottom), in libapriltag's order. The image is
  /// converted to grey with integer Rec. 601 luma weights. Throws UserError for an empty image
  /// or one whose buffer does not match width x height x 3.
  std::vector<TagDetection> Detect(const RgbImage& image);

  const TagDetectorOptions& options() const { return options_; }

 private:
  TagDetectorOptions options_;
  apriltag_family* family_ = nullptr;
  apriltag_detector* detector_ = nullptr;
};

}  // namespace recon::tags
