#include "devices/tags/tag_detector.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <memory>
#include <string>

#include "engine/core/error.h"

namespace recon::tags {
namespace {

struct DetectionsDeleter {
  void operator()(zarray_t* detections) const { apriltag_detections_destroy(detections); }
};

// Rec. 601 luma in integers (weights sum to 256), so the grey image, and hence the detections, are
// the same on every platform.
std::vector<uint8_t> ToGray(const RgbImage& image) {
  std::vector<uint8_t> gray(static_cast<size_t>(image.width) * image.height);
  const uint8_t* rgb = image.rgb.data();
  for (size_t i = 0; i < gray.size(); ++i, rgb += 3) {
    gray[i] = static_cast<uint8_t>((77 * rgb[0] + 150 * rgb[1] + 29 * rgb[2] + 128) >> 8);
  }
  return gray;
}

}  // namespace

TagDetector::TagDetector(TagDetectorOptions options) : options_(options) {
  if (!(options_.quad_decimate >= 1.0)) {
    throw UserError("TagDetector: quad_decimate must be at least 1, got " +
                    std::to_string(options_.quad_decimate));
  }
  if (!(options_.quad_sigma >= 0.0)) {
    throw UserError("TagDetector: quad_sigma must not be negative, got " +
                    std::to_string(options_.quad_sigma));
  }
  if (options_.nthreads < 1) {
    throw UserError("TagDetector: nthreads must be at least 1, got " +
                    std::to_string(options_.nthreads));
  }
  // libapriltag 3.3 cannot decode more than 2 corrected bits (see apriltag.h).
  if (options_.max_hamming < 0 || options_.max_hamming > 2) {
    throw UserError("TagDetector: max_hamming must be 0, 1 or 2, got " +
                    std::to_string(options_.max_hamming));
  }
  family_ = tag36h11_create();
  detector_ = apriltag_detector_create();
  apriltag_detector_add_family_bits(detector_, family_, options_.max_hamming);
  detector_->quad_decimate = static_cast<float>(options_.quad_decimate);
  detector_->quad_sigma = static_cast<float>(options_.quad_sigma);
  detector_->nthreads = options_.nthreads;
  detector_->refine_edges = options_.refine_edges;
}

TagDetector::~TagDetector() {
  // The detector refers to the family, so it goes first.
  apriltag_detector_destroy(detector_);
  tag36h11_destroy(family_);
}

std::vector<TagDetection> TagDetector::Detect(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw UserError("TagDetector::Detect: empty image (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")");
  }
  if (image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw UserError("TagDetector::Detect: a " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " RGB image needs " +
                    std::to_string(static_cast<size_t>(image.width) * image.height * 3) +
                    " bytes, got " + std::to_string(image.rgb.size()));
  }
  std::vector<uint8_t> gray = ToGray(image);
  // libapriltag reads the image without keeping it, so it can borrow our buffer.
  image_u8_t view{image.width, image.height, image.width, gray.data()};
  std::unique_ptr<zarray_t, DetectionsDeleter> found(apriltag_detector_detect(detector_, &view));

  std::vector<TagDetection> detections;
  detections.reserve(zarray_size(found.get()));
  for (int i = 0; i < zarray_size(found.get()); ++i) {
    apriltag_detection_t* raw = nullptr;
    zarray_get(found.get(), i, &raw);
    TagDetection detection;
    detection.id = raw->id;
    detection.hamming = raw->hamming;
    detection.decision_margin = raw->decision_margin;
    detection.center_px = {raw->c[0], raw->c[1]};
    for (int k = 0; k < 4; ++k) detection.corners_px[k] = {raw->p[k][0], raw->p[k][1]};
    for (int k = 0; k < 9; ++k) detection.homography[k] = raw->H->data[k];
    detections.push_back(detection);
  }
  return detections;
}

}  // namespace recon::tags
