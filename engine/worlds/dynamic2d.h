#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/worlds/vec2.h"
#include "engine/worlds/world.h"

namespace recon::worlds {

/// How a Dynamic2D world is configured. See docs/worlds.md for every setting.
struct Dynamic2DOptions {
  /// Where the beacon sits: "none" (the Baseline, d = 0), "exact", "partial", "other", "random",
  /// "exact+other", "exact+random" or "distance".
  std::string placement = "exact";
  /// Standard deviation of zero-mean Gaussian noise added to every beacon component (0 = none).
  double noise_sigma = 0.0;
  /// Reproduce the two slips of the authors' code (Other reads the robot when red is object 0;
  /// play images draw the undisplaced robot). Off by default.
  bool authors_compat = false;
  /// "image" (3x32x32, the paper) or "state" (the 14-vector robot xy, object xy, colours).
  std::string observation = "image";
};

/// The full state of a Dynamic2D scenario. Objects are indexed 0..3 in the order they were placed
/// on the circle (angles t, t+pi/2, t+pi, t-pi/2).
struct Dynamic2DState {
  Vec2 robot{0.0, 0.0};
  std::array<Vec2, 4> objects{};
  /// Colour value per object: 0 green, 5 olive, 10 red.
  std::array<double, 4> colours{};
  /// Index of the red (task-relevant) object.
  int red = 0;
};

/// The authors' Dynamic 2D world (REFERENCE.md section 2): four objects circle the origin
/// anticlockwise; the robot must move away from the red one. Observations are 3x32x32 images (or
/// the 14-vector state); the reward is the final robot-red distance (higher is better).
class Dynamic2D : public World {
 public:
  static constexpr int kNumObjects = 4;
  static constexpr int kImageSize = 32;
  static constexpr int kImageValues = 3 * kImageSize * kImageSize;
  static constexpr int kStateSize = 14;
  static constexpr int kEpisodeLength = 10;
  /// The reward is taken right after the robot's 9th move, before the objects rotate again: the
  /// authors' episode is 10 time points (the start and 9 moves), and only this timing gives their
  /// expert score of 17.785 (docs/worlds.md). The 10th action is executed but not scored.
  static constexpr int kScoredSteps = 9;
  static constexpr int kPlayPerScenario = 3;
  static constexpr double kCircleRadius = 10.0;
  /// Half the width of the square the image shows: [-12, 12] in both axes.
  static constexpr double kViewHalfWidth = 12.0;
  static constexpr double kRotationPerStepRad = M_PI / 24.0;
  /// Play samples displace the robot by up to this distance.
  static constexpr double kPlayMaxDisplacement = 10.0;

  /// Throws UserError for an unknown placement or observation, or a negative or non-finite sigma.
  explicit Dynamic2D(const Dynamic2DOptions& options);

  std::string Name() const override;
  DataSpec Spec() const override;
  int EpisodeLength() const override { return kEpisodeLength; }
  void Reset(uint64_t seed) override;
  Observation Observe() const override;
  void Step(const std::vector<float>& u) override;
  std::vector<float> ExpertAction() const override;
  std::vector<float> BeaconReading() override;
  PlaySample SamplePlay() override;
  int PlaySamplesPerScenario() const override { return kPlayPerScenario; }
  /// Robot-red distance; once kScoredSteps steps have run, the distance at that moment.
  double EpisodeMetric() const override;
  /// The final distance to the red object, higher is better (a reward: the robot flees it).
  WorldTraits Traits() const override;

  const Dynamic2DOptions& options() const { return options_; }
  const Dynamic2DState& state() const { return state_; }
  /// The scenario's image background, channels first, integers in [225, 255].
  const std::vector<float>& background() const { return background_; }
  /// The object a "random" placement reads in this scenario (never the red one).
  int random_object() const { return random_object_; }
  /// Steps taken since Reset.
  int steps() const { return steps_; }

  /// Valid placement names, in the order they are documented.
  static const std::vector<std::string>& Placements();
  /// Beacon size d of a placement (throws UserError for an unknown one).
  static int BeaconDim(const std::string& placement);
  /// Pixel index of coordinate s: round(32 (s + 12) / 24), ties to even. May lie outside [0, 31].
  static int PixelIndex(double s);
  /// Renders `state` over `background` (kImageValues floats, channels first): robot first (red
  /// and green set to 0), then the objects, each a 2x2 block clipped to the image.
  static std::vector<float> RenderImage(const Dynamic2DState& state,
                                        const std::vector<float>& background);
  /// The 14-vector: robot xy, object xy in index order, colour values.
  static std::vector<float> StateVector(const Dynamic2DState& state);

 private:
  std::vector<float> ObserveY(const Dynamic2DState& state) const;
  /// Noise-free beacon reading of `state` for the configured placement.
  std::vector<double> CleanBeacon(const Dynamic2DState& state) const;
  std::vector<float> AddNoise(const std::vector<double>& clean, Rng& rng) const;

  Dynamic2DOptions options_;
  Dynamic2DState state_;
  std::vector<float> background_;
  int random_object_ = 1;
  int steps_ = 0;
  double scored_distance_ = 0.0;
  // Separate streams so that drawing play samples never changes a demonstration's beacon noise.
  Rng noise_rng_{0};
  Rng play_rng_{0};
};

/// Builds a Dynamic2D world; throws UserError listing the valid names for an unknown placement.
std::unique_ptr<World> MakeDynamic2D(const Dynamic2DOptions& options);

}  // namespace recon::worlds
