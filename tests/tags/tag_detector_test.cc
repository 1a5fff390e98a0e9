#include "devices/tags/tag_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "tests/tags/synthetic_scene.h"

namespace recon::tags {
namespace {

using testing::Occluder;
using testing::PlacedTag;
using testing::SceneCamera;
using testing::SceneOptions;

// A camera 1 m above the table looking straight down, image up = table +y (MuJoCo's default
// orientation), fovy 60: 1 cm on the table is about 4.2 pixels.
SceneCamera TopDownCamera() { return SceneCamera{}; }

// `count` tags with distinct ids, random yaw and size (5..8 cm unless given), spread over the
// camera's view without overlapping (rejection sampling), all on z = 0.
std::vector<PlacedTag> RandomTags(int count, uint64_t seed, double min_size_m = 0.05,
                                  double max_size_m = 0.08) {
  Rng rng(seed);
  std::vector<PlacedTag> tags;
  while (static_cast<int>(tags.size()) < count) {
    PlacedTag tag;
    tag.id = static_cast<int>(rng.UniformInt(587));
    tag.size_m = rng.Uniform(min_size_m, max_size_m);
    tag.yaw_rad = rng.Uniform(-M_PI, M_PI);
    tag.center_m = {rng.Uniform(-0.6, 0.6), rng.Uniform(-0.42, 0.42), 0.0};
    bool clear = true;
    for (const PlacedTag& other : tags) {
      clear = clear && other.id != tag.id && (other.center_m - tag.center_m).norm() > 0.15;
    }
    if (clear) tags.push_back(tag);
  }
  return tags;
}

// Detections keyed by id; fails the test on a duplicate.
std::map<int, TagDetection> ById(const std::vector<TagDetection>& detections) {
  std::map<int, TagDetection> by_id;
  for (const TagDetection& d : detections) {
    EXPECT_TRUE(by_id.emplace(d.id, d).second) << "id " << d.id << " detected twice";
  }
  return by_id;
}

TEST(ApriltagDetectorTest, FindsEveryTagWithItsIdOnAWhiteTable) {
  const std::vector<PlacedTag> tags = RandomTags(8, /*seed=*/11);
  const RgbImage image = testing::RenderScene(TopDownCamera(), tags, {}, SceneOptions{});
  TagDetector detector;
  const std::vector<TagDetection> detections = detector.Detect(image);
  ASSERT_EQ(detections.size(), tags.size());
  const auto by_id = ById(detections);
  for (const PlacedTag& tag : tags) {
    ASSERT_TRUE(by_id.count(tag.id)) << "tag " << tag.id << " not found";
    EXPECT_EQ(by_id.at(tag.id).hamming, 0);
    EXPECT_GT(by_id.at(tag.id).decision_margin, 50.0);
  }
}

TEST(ApriltagDetectorTest, FindsEveryTagOnATexturedNoisyTable) {
  for (const uint64_t seed : {12u, 13u, 14u}) {
    const std::vector<PlacedTag> tags = RandomTags(8, seed);
    SceneOptions options;
    options.textured_table = true;
    options.noise_sigma = 3.0;
    options.seed = seed;
    const RgbImage image = testing::RenderScene(TopDownCamera(), tags, {}, options);
    TagDetector detector;
    const auto by_id = ById(detector.Detect(image));
    EXPECT_EQ(by_id.size(), tags.size()) << "seed " << seed;
    for (const PlacedTag& tag : tags) {
      EXPECT_TRUE(by_id.count(tag.id)) << "seed " << seed << ": tag " << tag.id << " not found";
    }
  }
}

// Corners come back in libapriltag's order: the images of tag-local (-1, -1), (1, -1), (1, 1),
// (-1, 1) with y toward the printed top row (bottom-left first, counter-clockwise as seen). The
// mean error over many corners also pins the pixel convention: were pixel centres on integers,
// every coordinate would be off by -0.5.
TEST(ApriltagDetectorTest, CornersAndCentreMatchTheProjectionToSubpixelPrecision) {
  double sum_dx = 0.0, sum_dy = 0.0, sum_sq = 0.0;
  int n = 0;
  for (const uint64_t seed : {21u, 22u, 23u}) {
    const std::vector<PlacedTag> tags = RandomTags(8, seed);
    const SceneCamera camera = TopDownCamera();
    TagDetector detector;
    const auto by_id = ById(detector.Detect(testing::RenderScene(camera, tags, {}, {})));
    for (const PlacedTag& tag : tags) {
      ASSERT_TRUE(by_id.count(tag.id));
      const TagDetection& d = by_id.at(tag.id);
      const std::vector<Eigen::Vector3d> corners = testing::TagCorners(tag);
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d error = d.corners_px[k] - testing::ProjectPoint(camera, corners[k]);
        EXPECT_LT(error.norm(), 0.5) << "tag " << tag.id << " corner " << k;
        sum_dx += error.x();
        sum_dy += error.y();
        sum_sq += error.squaredNorm();
        ++n;
      }
      const Eigen::Vector2d centre_error =
          d.center_px - testing::ProjectPoint(camera, tag.center_m);
      EXPECT_LT(centre_error.norm(), 0.3) << "tag " << tag.id;
    }
  }
  const double rms = std::sqrt(sum_sq / n);
  std::cout << "corner error over " << n << " corners: rms " << rms << " px, mean (" << sum_dx / n
            << ", " << sum_dy / n << ") px\n";
  EXPECT_LT(rms, 0.25);
  EXPECT_LT(std::abs(sum_dx / n), 0.05);
  EXPECT_LT(std::abs(sum_dy / n), 0.05);
}

TEST(ApriltagDetectorTest, BlankImagesGiveNoDetections) {
  TagDetector detector;
  const SceneCamera camera = TopDownCamera();
  EXPECT_TRUE(detector.Detect(testing::RenderScene(camera, {}, {}, {})).empty()) << "white";
  for (const uint64_t seed : {31u, 32u, 33u, 34u}) {
    SceneOptions options;
    options.textured_table = true;
    options.noise_sigma = 4.0;
    options.seed = seed;
    EXPECT_TRUE(detector.Detect(testing::RenderScene(camera, {}, {}, options)).empty())
        << "textured table, seed " << seed;
  }
  RgbImage black;
  black.width = 640;
  black.height = 480;
  black.rgb.assign(640 * 480 * 3, 0);
  EXPECT_TRUE(detector.Detect(black).empty()) << "black";
}

// A tag running off the image edge, or half hidden, must never come back as another id. A fully
// visible tag in the same frame checks that the detector works at all in these images.
TEST(ApriltagDetectorTest, CutOrOccludedTagIsNeverReportedWithAWrongId) {
  const SceneCamera camera = TopDownCamera();
  const PlacedTag reference{17, {-0.3, 0.2, 0.0}, 0.4, 0.07};
  TagDetector detector;
  int cut_tags_seen = 0;
  // Tag 233, 7 cm, slid across the right image edge (x = 0.77 m at 1 m height, fovy 60, 4:3).
  for (int step = 0; step < 8; ++step) {
    const double x = 0.70 + 0.015 * step;
    for (const double yaw : {0.0, 0.5}) {
      const PlacedTag cut{233, {x, -0.1, 0.0}, yaw, 0.07};
      const auto by_id =
          ById(detector.Detect(testing::RenderScene(camera, {reference, cut}, {}, {})));
      EXPECT_TRUE(by_id.count(reference.id)) << "x " << x;
      for (const auto& [id, d] : by_id) {
        EXPECT_TRUE(id == reference.id || id == cut.id) << "x " << x << ": wrong id " << id;
        if (id == cut.id) ++cut_tags_seen;
      }
    }
  }
  // Fully inside at x = 0.70 (both yaws), so at least those two were read.
  EXPECT_GE(cut_tags_seen, 2);
  std::cout << "tag sliding off the edge: read in " << cut_tags_seen << " of 16 frames\n";

  // Tag 402 at the centre (8 cm = 33 px), hidden by boxes of different shapes.
  const PlacedTag hidden{402, {0.0, 0.0, 0.0}, 0.0, 0.08};
  const Eigen::Vector2d c = testing::ProjectPoint(camera, hidden.center_m);
  const int col = static_cast<int>(c.x()), row = static_cast<int>(c.y());
  const std::vector<Occluder> occluders = {
      {col - 30, row - 30, col, row, 90},            // top-left quarter
      {col - 30, row - 4, col + 30, row + 4, 90},    // a stripe through the data
      {col, row - 30, col + 30, row + 30, 200},      // the right half, in light grey
      {col - 3, row - 3, col + 3, row + 3, 255},     // a few data cells whitened
      {col + 10, row + 10, col + 30, row + 30, 0}};  // bottom-right corner in black
  int hidden_seen = 0;
  for (const Occluder& occluder : occluders) {
    const auto by_id =
        ById(detector.Detect(testing::RenderScene(camera, {reference, hidden}, {occluder}, {})));
    EXPECT_TRUE(by_id.count(reference.id));
    hidden_seen += static_cast<int>(by_id.count(hidden.id));
    for (const auto& [id, d] : by_id) {
      EXPECT_TRUE(id == reference.id || id == hidden.id)
          << "occluder at " << occluder.col0 << "," << occluder.row0 << ": wrong id " << id;
    }
  }
  std::cout << "occluded tag: read despite " << hidden_seen << " of " << occluders.size()
            << " occluders\n";
}

// Halving the resolution for quad detection loses tags below about 25 pixels (6 cm here), so
// this uses 9..11 cm tags.
TEST(ApriltagDetectorTest, DecimationAndThreadsStillFindLargeTags) {
  const std::vector<PlacedTag> tags = RandomTags(6, /*seed=*/41, 0.09, 0.11);
  const RgbImage image = testing::RenderScene(TopDownCamera(), tags, {}, {});
  TagDetectorOptions options;
  options.quad_decimate = 2.0;
  options.nthreads = 2;
  TagDetector detector(options);
  const auto by_id = ById(detector.Detect(image));
  EXPECT_EQ(by_id.size(), tags.size());
  for (const PlacedTag& tag : tags) EXPECT_TRUE(by_id.count(tag.id)) << tag.id;
  // The detector can be used again on the next frame.
  EXPECT_EQ(detector.Detect(image).size(), tags.size());
}

TEST(ApriltagDetectorTest, RejectsBadOptionsAndMalformedImages) {
  EXPECT_THROW(TagDetector(TagDetectorOptions{.quad_decimate = 0.5}), UserError);
  EXPECT_THROW(TagDetector(TagDetectorOptions{.quad_sigma = -1.0}), UserError);
  EXPECT_THROW(TagDetector(TagDetectorOptions{.nthreads = 0}), UserError);
  EXPECT_THROW(TagDetector(TagDetectorOptions{.max_hamming = 3}), UserError);
  TagDetector detector;
  EXPECT_THROW(detector.Detect(RgbImage{}), UserError);
  RgbImage short_buffer;
  short_buffer.width = 64;
  short_buffer.height = 48;
  short_buffer.rgb.assign(64 * 48, 255);
  EXPECT_THROW(detector.Detect(short_buffer), UserError);
}

}  // namespace
}  // namespace recon::tags
