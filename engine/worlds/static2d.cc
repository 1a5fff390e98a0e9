#include "engine/worlds/static2d.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/scenario_streams.h"

namespace recon::worlds {
Static2D::Static2D(const Static2DOptions& options) : options_(options) {
  BeaconDim(options_.placement);  // validates the name
  if (!std::isfinite(options_.noise_sigma) || options_.noise_sigma < 0.0) {
    std::ostringstream msg;
    msg << "beacon noise sigma must be a finite number >= 0, got " << options_.noise_sigma;
    throw UserError(msg.str());
  }
  Reset(0);
}

const std::vector<std::string>& Static2D::Placements() {
  static const std::vector<std::string> kPlacements = {"none", "position", "distance"};
  return kPlacements;
}

int Static2D::BeaconDim(const std::string& placement) {
  if (placement == "none") return 0;
  if (placement == "position") return 2;
  if (placement == "distance") return 1;
  throw UserError("unknown beacon placement '" + placement +
                  "' for static2d; valid placements: " + JoinNames(Placements()));
}

DataSpec Static2D::Spec() const {
  DataSpec spec;
  spec.x_dim = 2;
  spec.y_shape = {2 * kNumObjects};
  spec.b_dim = BeaconDim(options_.placement);
  spec.u_dim = 2;
  return spec;
}

Static2DState Static2D::DrawScenario(Rng& rng, double robot_half_width) {
  const Vec2 centre = {rng.Uniform(-kTargetHalfWidth, kTargetHalfWidth),
                       rng.Uniform(-kTargetHalfWidth, kTargetHalfWidth)};
  const double angle = rng.Uniform(-M_PI, M_PI);
  const double spacing = rng.Uniform(kMinSpacing, kMaxSpacing);
  const Vec2 offset = {spacing * std::cos(angle), spacing * std::sin(angle)};
  // Geometric order: one end, the centre, the other end. Then shuffle (Fisher-Yates) so the
  // learner has to work out which slot holds the middle object.
  std::array<Vec2, kNumObjects> line = {Vec2{centre[0] - offset[0], centre[1] - offset[1]}, centre,
                                        Vec2{centre[0] + offset[0], centre[1] + offset[1]}};
  std::array<int, kNumObjects> order = {0, 1, 2};
  for (int i = kNumObjects - 1; i > 0; --i) {
    std::swap(order[i], order[rng.UniformInt(i + 1)]);
  }
  Static2DState state;
  for (int slot = 0; slot < kNumObjects; ++slot) {
    state.objects[slot] = line[order[slot]];
    if (order[slot] == 1) state.centre = slot;
  }
  state.robot = {rng.Uniform(-robot_half_width, robot_half_width),
                 rng.Uniform(-robot_half_width, robot_half_width)};
  return state;
}

void Static2D::Reset(uint64_t seed) {
  Rng rng(Rng::Derive(seed, kScenarioStream));
  state_ = DrawScenario(rng, kStartHalfWidth);
  noise_rng_.Seed(Rng::Derive(seed, kNoiseStream));
  play_rng_.Seed(Rng::Derive(seed, kPlayStream));
}

std::vector<float> Static2D::ObjectVector(const Static2DState& state) {
  std::vector<float> y;
  y.reserve(2 * kNumObjects);
  for (const Vec2& p : state.objects) {
    y.push_back(static_cast<float>(p[0]));
    y.push_back(static_cast<float>(p[1]));
  }
  return y;
}

Observation Static2D::Observe() const {
  return {{static_cast<float>(state_.robot[0]), static_cast<float>(state_.robot[1])},
          ObjectVector(state_)};
}

void Static2D::Step(const std::vector<float>& u) {
  if (u.size() != 2) {
    throw std::invalid_argument("Static2D::Step: action must have 2 values, got " +
                                std::to_string(u.size()));
  }
  // Objects are static: the paper's objects only move once grasped, which ends the task.
  state_.robot[0] += u[0];
  state_.robot[1] += u[1];
}

std::vector<float> Static2D::ExpertAction() const {
  const Vec2& target = state_.objects[state_.centre];
  const double dist = Distance(state_.robot, target);
  if (dist == 0.0) return {0.0f, 0.0f};
  // A unit step, shortened on the last one so the expert stops on the target instead of
  // oscillating around it.
  const double scale = std::min(kStepLength, dist) / dist;
  return {static_cast<float>((target[0] - state_.robot[0]) * scale),
          static_cast<float>((target[1] - state_.robot[1]) * scale)};
}

std::vector<float> Static2D::Beacon(const Static2DState& state, Rng& rng) const {
  const Vec2& target = state.objects[state.centre];
  std::vector<double> clean;
  if (options_.placement == "position") clean = {target[0], target[1]};
  if (options_.placement == "distance") clean = {Distance(state.robot, target)};
  std::vector<float> b(clean.size());
  for (size_t i = 0; i < clean.size(); ++i) {
    const double noise = options_.noise_sigma > 0.0 ? options_.noise_sigma * rng.Normal() : 0.0;
    b[i] = static_cast<float>(clean[i] + noise);
  }
  return b;
}

std::vector<float> Static2D::BeaconReading() { return Beacon(state_, noise_rng_); }

PlaySample Static2D::SamplePlay() {
  // The paper's play data come from random initialisations, not from the current scenario: a
  // fresh layout and robot position, drawn from the play stream so the scenario is untouched.
  const Static2DState play_state = DrawScenario(play_rng_, kPlayRobotHalfWidth);
  PlaySample play;
  play.x = {static_cast<float>(play_state.robot[0]), static_cast<float>(play_state.robot[1])};
  play.y = ObjectVector(play_state);
  play.b = Beacon(play_state, play_rng_);
  return play;
}

double Static2D::EpisodeMetric() const {
  return Distance(state_.robot, state_.objects[state_.centre]);
}

WorldTraits Static2D::Traits() const {
  WorldTraits traits;
  traits.metric_name = "final distance between the robot and the centre object (lower is better)";
  return traits;
}

std::unique_ptr<World> MakeStatic2D(const Static2DOptions& options) {
  return std::make_unique<Static2D>(options);
}

}  // namespace recon::worlds
