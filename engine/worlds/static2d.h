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

/// How a Static2D world is configured. See docs/worlds.md.
struct Static2DOptions {
  /// "none" (the Baseline, d = 0), "position" (the centre object's xy, d = 2, RECON-P) or
  /// "distance" (|robot - centre|, d = 1, RECON-D).
  std::string placement = "position";
  /// Standard deviation of zero-mean Gaussian noise added to every beacon component (0 = none).
  double noise_sigma = 0.0;
};

/// The state of a Static2D scenario. Objects are stored in the shuffled order y lists them in.
struct Static2DState {
  Vec2 robot{0.0, 0.0};
  std::array<Vec2, 3> objects{};
  /// Slot of `objects` that holds the centre (task-relevant) object.
  int centre = 0;
};

/// The paper's Static 2D world, designed from its text (REFERENCE.md section 3; the numbers are
/// ours, see docs/worlds.md): three static objects on a randomly placed line, listed in random
/// order; the robot must reach the middle one. The score is the final distance to it (lower is
/// better).
class Static2D : public World {
 public:
  static constexpr int kNumObjects = 3;
  static constexpr int kEpisodeLength = 10;
  static constexpr int kPlayPerScenario = 3;
  /// The line's centre (the target) is uniform in the square [-kTargetHalfWidth, +]^2.
  static constexpr double kTargetHalfWidth = 4.0;
  /// The robot starts uniform in the square [-kStartHalfWidth, +]^2.
  static constexpr double kStartHalfWidth = 2.0;
  /// Distance between neighbouring objects, uniform in [kMinSpacing, kMaxSpacing).
  static constexpr double kMinSpacing = 1.5;
  static constexpr double kMaxSpacing = 3.0;
  /// Play samples put the robot uniform in this square, which holds every start, every target and
  /// so every point of the expert's straight path between them.
  static constexpr double kPlayRobotHalfWidth = kTargetHalfWidth;
  /// The expert's (and the paper's) step length.
  static constexpr double kStepLength = 1.0;

  /// Throws UserError for an unknown placement or a negative or non-finite sigma.
  explicit Static2D(const Static2DOptions& options);

  std::string Name() const override { return "static2d"; }
  DataSpec Spec() const override;
  int EpisodeLength() const override { return kEpisodeLength; }
  void Reset(uint64_t seed) override;
  Observation Observe() const override;
  void Step(const std::vector<float>& u) override;
  std::vector<float> ExpertAction() const override;
  std::vector<float> BeaconReading() override;
  PlaySample SamplePlay() override;
  int PlaySamplesPerScenario() const override { return kPlayPerScenario; }
  double EpisodeMetric() const override;
  /// The final distance to the centre object, lower is better.
  WorldTraits Traits() const override;

  const Static2DOptions& options() const { return options_; }
  const Static2DState& state() const { return state_; }

  /// Valid placement names.
  static const std::vector<std::string>& Placements();
  /// Beacon size d of a placement (throws UserError for an unknown one).
  static int BeaconDim(const std::string& placement);
  /// Draws a layout and a robot position from `rng`; the robot uniform in the square of the given
  /// half width.
  static Static2DState DrawScenario(Rng& rng, double robot_half_width);

 private:
  static std::vector<float> ObjectVector(const Static2DState& state);
  std::vector<float> Beacon(const Static2DState& state, Rng& rng) const;

  Static2DOptions options_;
  Static2DState state_;
  // Separate streams so that drawing play samples never changes a demonstration's beacon noise.
  Rng noise_rng_{0};
  Rng play_rng_{0};
};

/// Builds a Static2D world; throws UserError listing the valid names for an unknown placement.
std::unique_ptr<World> MakeStatic2D(const Static2DOptions& options);

}  // namespace recon::worlds
