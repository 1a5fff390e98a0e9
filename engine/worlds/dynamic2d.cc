#include "engine/worlds/dynamic2d.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/scenario_streams.h"

namespace recon::worlds {
namespace {

constexpr int kBackgroundMin = 225;
constexpr int kBackgroundMax = 255;
constexpr double kGreen = 0.0;
constexpr double kOlive = 5.0;
constexpr double kRed = 10.0;

// The four pixel indices {i-1, i} clamped into the image, as the reference clips them.
std::array<int, 2> BlockIndices(double s) {
  const int i = Dynamic2D::PixelIndex(s);
  const int hi = Dynamic2D::kImageSize - 1;
  return {std::clamp(i - 1, 0, hi), std::clamp(i, 0, hi)};
}

// Sets channel values over an item's 2x2 block; a negative value leaves that channel alone.
void DrawBlock(const Vec2& p, const std::array<float, 3>& rgb, std::vector<float>& image) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return;  // a diverged rollout: nothing to draw
  constexpr int n = Dynamic2D::kImageSize;
  for (int a : BlockIndices(p[0])) {
    for (int b : BlockIndices(p[1])) {
      for (int c = 0; c < 3; ++c) {
        if (rgb[c] >= 0.0f) image[c * n * n + a * n + b] = rgb[c];
      }
    }
  }
}

}  // namespace

Dynamic2D::Dynamic2D(const Dynamic2DOptions& options) : options_(options) {
  BeaconDim(options_.placement);  // validates the name
  if (options_.observation != "image" && options_.observation != "state") {
    throw UserError("unknown observation '" + options_.observation +
                    "' for dynamic2d; valid observations: image, state");
  }
  if (!std::isfinite(options_.noise_sigma) || options_.noise_sigma < 0.0) {
    std::ostringstream msg;
    msg << "beacon noise sigma must be a finite number >= 0, got " << options_.noise_sigma;
    throw UserError(msg.str());
  }
  Reset(0);
}

const std::vector<std::string>& Dynamic2D::Placements() {
  static const std::vector<std::string> kPlacements = {
      "none", "exact", "partial", "other", "random", "exact+other", "exact+random", "distance"};
  return kPlacements;
}

int Dynamic2D::BeaconDim(const std::string& placement) {
  if (placement == "none") return 0;
  if (placement == "partial" || placement == "distance") return 1;
  if (placement == "exact" || placement == "other" || placement == "random") return 2;
  if (placement == "exact+other" || placement == "exact+random") return 4;
  throw UserError("unknown beacon placement '" + placement +
                  "' for dynamic2d; valid placements: " + JoinNames(Placements()));
}

std::string Dynamic2D::Name() const {
  return options_.observation == "state" ? "dynamic2d-state" : "dynamic2d";
}

DataSpec Dynamic2D::Spec() const {
  DataSpec spec;
  spec.x_dim = 2;
  spec.y_shape = options_.observation == "state" ? std::vector<int64_t>{kStateSize}
                                                 : std::vector<int64_t>{3, kImageSize, kImageSize};
  spec.b_dim = BeaconDim(options_.placement);
  spec.u_dim = 2;
  return spec;
}

void Dynamic2D::Reset(uint64_t seed) {
  Rng rng(Rng::Derive(seed, kScenarioStream));
  const double t = rng.Uniform(-M_PI, M_PI);
  const std::array<double, kNumObjects> angles = {t, t + M_PI / 2, t + M_PI, t - M_PI / 2};
  state_.robot = {0.0, 0.0};
  for (int i = 0; i < kNumObjects; ++i) {
    state_.objects[i] = {kCircleRadius * std::cos(angles[i]), kCircleRadius * std::sin(angles[i])};
  }
  // One object is green; the one two places before it (i.e. opposite it) is red.
  const int green = static_cast<int>(rng.UniformInt(kNumObjects));
  state_.colours.fill(kOlive);
  state_.colours[green] = kGreen;
  state_.red = (green + kNumObjects - 2) % kNumObjects;
  state_.colours[state_.red] = kRed;

  background_.resize(kImageValues);
  for (float& v : background_) {
    v = static_cast<float>(kBackgroundMin + rng.UniformInt(kBackgroundMax - kBackgroundMin + 1));
  }
  // Drawn whatever the placement, so the same seed gives the same scenario under every placement.
  const int k = static_cast<int>(rng.UniformInt(kNumObjects - 1));
  random_object_ = (state_.red + 1 + k) % kNumObjects;

  steps_ = 0;
  scored_distance_ = 0.0;
  noise_rng_.Seed(Rng::Derive(seed, kNoiseStream));
  play_rng_.Seed(Rng::Derive(seed, kPlayStream));
}

int Dynamic2D::PixelIndex(double s) {
  // nearbyint honours the default rounding mode, round half to even, as numpy's round does.
  const double v = std::nearbyint(kImageSize * (s + kViewHalfWidth) / (2.0 * kViewHalfWidth));
  // Saturate so the int conversion is defined; every index outside [0, 31] clips the same way.
  if (std::isnan(v)) return -2;
  return static_cast<int>(std::clamp(v, -2.0, static_cast<double>(kImageSize + 1)));
}

std::vector<float> Dynamic2D::RenderImage(const Dynamic2DState& state,
                                          const std::vector<float>& background) {
  if (static_cast<int>(background.size()) != kImageValues) {
    throw std::invalid_argument("Dynamic2D::RenderImage: background must hold 3x32x32 values");
  }
  std::vector<float> image = background;
  DrawBlock(state.robot, {0.0f, 0.0f, -1.0f}, image);  // blue shows through
  for (int i = 0; i < kNumObjects; ++i) {
    const double c = state.colours[i];
    DrawBlock(
        state.objects[i],
        {static_cast<float>(c / 10.0 * 255.0), static_cast<float>((1.0 - c / 10.0) * 255.0), 0.0f},
        image);
  }
  return image;
}

std::vector<float> Dynamic2D::StateVector(const Dynamic2DState& state) {
  std::vector<float> v;
  v.reserve(kStateSize);
  v.push_back(static_cast<float>(state.robot[0]));
  v.push_back(static_cast<float>(state.robot[1]));
  for (const Vec2& p : state.objects) {
    v.push_back(static_cast<float>(p[0]));
    v.push_back(static_cast<float>(p[1]));
  }
  for (double c : state.colours) v.push_back(static_cast<float>(c));
  return v;
}

std::vector<float> Dynamic2D::ObserveY(const Dynamic2DState& state) const {
  return options_.observation == "state" ? StateVector(state) : RenderImage(state, background_);
}

Observation Dynamic2D::Observe() const {
  return {{static_cast<float>(state_.robot[0]), static_cast<float>(state_.robot[1])},
          ObserveY(state_)};
}

void Dynamic2D::Step(const std::vector<float>& u) {
  if (u.size() != 2) {
    throw std::invalid_argument("Dynamic2D::Step: action must have 2 values, got " +
                                std::to_string(u.size()));
  }
  state_.robot[0] += u[0];  // no clipping, as in the reference
  state_.robot[1] += u[1];
  if (++steps_ == kScoredSteps)
    scored_distance_ = Distance(state_.robot, state_.objects[state_.red]);
  const double c = std::cos(kRotationPerStepRad);
  const double s = std::sin(kRotationPerStepRad);
  for (Vec2& p : state_.objects) p = {c * p[0] - s * p[1], s * p[0] + c * p[1]};
}

std::vector<float> Dynamic2D::ExpertAction() const {
  const Vec2& red = state_.objects[state_.red];
  const double dist = Distance(state_.robot, red);
  // The reference stops once the robot is on the circle (never reached in 10 unit steps); a zero
  // distance has no direction, so stand still there too rather than divide by zero.
  if (std::hypot(state_.robot[0], state_.robot[1]) >= kCircleRadius || dist == 0.0) {
    return {0.0f, 0.0f};
  }
  return {static_cast<float>((state_.robot[0] - red[0]) / dist),
          static_cast<float>((state_.robot[1] - red[1]) / dist)};
}

std::vector<double> Dynamic2D::CleanBeacon(const Dynamic2DState& state) const {
  const std::string& p = options_.placement;
  const Vec2& red = state.objects[state.red];
  // The authors index [robot, obj0..obj3] with red-1 without wrapping among the objects, so when
  // red is object 0 their Other beacon reads the robot. We wrap unless asked to reproduce that.
  const Vec2& other = (options_.authors_compat && state.red == 0)
                          ? state.robot
                          : state.objects[(state.red + kNumObjects - 1) % kNumObjects];
  const Vec2& random = state.objects[random_object_];
  if (p == "none") return {};
  if (p == "exact") return {red[0], red[1]};
  if (p == "partial") return {red[0]};  // the x coordinate (the paper allows x or y)
  if (p == "other") return {other[0], other[1]};
  if (p == "random") return {random[0], random[1]};
  if (p == "exact+other") return {red[0], red[1], other[0], other[1]};
  if (p == "exact+random") return {red[0], red[1], random[0], random[1]};
  if (p == "distance") return {Distance(state.robot, red)};
  throw std::logic_error("Dynamic2D: placement validated at construction: " + p);
}

std::vector<float> Dynamic2D::AddNoise(const std::vector<double>& clean, Rng& rng) const {
  std::vector<float> b(clean.size());
  for (size_t i = 0; i < clean.size(); ++i) {
    const double noise = options_.noise_sigma > 0.0 ? options_.noise_sigma * rng.Normal() : 0.0;
    b[i] = static_cast<float>(clean[i] + noise);
  }
  return b;
}

std::vector<float> Dynamic2D::BeaconReading() { return AddNoise(CleanBeacon(state_), noise_rng_); }

PlaySample Dynamic2D::SamplePlay() {
  const double angle = play_rng_.Uniform(-M_PI, M_PI);
  const double radius = kPlayMaxDisplacement * play_rng_.Uniform();
  Dynamic2DState displaced = state_;
  displaced.robot[0] += radius * std::cos(angle);
  displaced.robot[1] += radius * std::sin(angle);
  PlaySample play;
  play.x = {static_cast<float>(displaced.robot[0]), static_cast<float>(displaced.robot[1])};
  // The authors render the undisplaced robot while x and b use the displaced one (a slip).
  play.y = ObserveY(options_.authors_compat ? state_ : displaced);
  play.b = AddNoise(CleanBeacon(displaced), play_rng_);
  return play;
}

double Dynamic2D::EpisodeMetric() const {
  if (steps_ >= kScoredSteps) return scored_distance_;
  return Distance(state_.robot, state_.objects[state_.red]);
}

WorldTraits Dynamic2D::Traits() const {
  WorldTraits traits;
  traits.metric_name =
      "final distance between the robot and the red object (reward, higher is better)";
  traits.higher_is_better = true;
  return traits;
}

std::unique_ptr<World> MakeDynamic2D(const Dynamic2DOptions& options) {
  return std::make_unique<Dynamic2D>(options);
}

}  // namespace recon::worlds
