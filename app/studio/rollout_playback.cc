#include "app/studio/rollout_playback.h"

#include <algorithm>
#include <filesystem>

#include "app/cli/session_world.h"
#include "engine/core/error.h"
#include "engine/learn/learner.h"
#include "engine/probe/saliency.h"
#include "engine/store/session.h"
#include "engine/teach/workflow.h"
#include "engine/worlds/tabletop.h"

namespace recon::studio {

namespace fs = std::filesystem;

namespace {
constexpr auto kStep = std::chrono::milliseconds(100);  // the arm's control period
}  // namespace

RolloutPlayback::RolloutPlayback(store::SessionManifest manifest, std::string session_dir)
    : manifest_(std::move(manifest)), session_dir_(std::move(session_dir)) {}

void RolloutPlayback::Reload() {
  methods_.clear();
  for (const char* method : {teach::kBaselineMethod, teach::kReconMethod}) {
    const fs::path path =
        fs::path(session_dir_) / store::Session::RolloutReplayRelativePath(method);
    if (!fs::exists(path)) continue;
    methods_.emplace(
        method,
        Method{store::RolloutReplayFile::Open(path.string()), std::nullopt, {}, {}, -1, -1, 0});
  }
  Show(scenario_, frame_);
  playing_ = false;
}

void RolloutPlayback::Show(int scenario, int frame) {
  int scenarios = 0;
  for (auto& [name, method] : methods_) {
    scenarios = std::max(scenarios, method.file.NumScenarios());
  }
  scenario_ = std::clamp(scenario, 0, std::max(0, scenarios - 1));
  frame_ = std::clamp(frame, 0, std::max(0, Frames() - 1));
  playing_ = false;
}

void RolloutPlayback::SetPlaying(bool playing, std::chrono::steady_clock::time_point now) {
  if (playing && frame_ >= Frames() - 1) frame_ = 0;
  playing_ = playing && Frames() > 1;
  next_step_ = now + kStep;
}

void RolloutPlayback::Tick(std::chrono::steady_clock::time_point now) {
  if (!playing_ || now < next_step_) return;
  next_step_ = now + kStep;
  if (++frame_ >= Frames() - 1) {
    frame_ = std::max(0, Frames() - 1);
    playing_ = false;
  }
}

const store::ScenarioReplay& RolloutPlayback::Scenario(Method& method) {
  const int index = std::min(scenario_, method.file.NumScenarios() - 1);
  if (!method.scenario || method.image_scenario != index) {
    method.scenario = method.file.ReadScenario(index);
    method.image_scenario = index;
    method.image_frame = -1;
  }
  return *method.scenario;
}

int RolloutPlayback::Frames() {
  int frames = 0;
  for (auto& [name, method] : methods_) {
    if (method.file.NumScenarios() == 0) continue;
    frames = std::max(frames, static_cast<int>(Scenario(method).states.size()));
  }
  return frames;
}

void RolloutPlayback::SetSaliency(ui::SaliencyMode mode) {
  saliency_ = mode;
  for (auto& [name, method] : methods_) method.image_frame = -1;  // drawn again
}

RgbImage RolloutPlayback::Draw(const std::string& name, Method& method,
                               worlds::SceneRenderer& renderer, int width, int height) {
  // The test scenes have no beacons: draw them in a world without any.
  if (!world_) world_ = cli::MakeSessionWorld(manifest_, "none");
  auto* tabletop = dynamic_cast<worlds::Tabletop*>(world_.get());
  if (tabletop == nullptr) throw UserError("rollout playback needs the arm cell");
  tabletop->ShowReplayState(method.scenario->states[static_cast<size_t>(method.image_frame)]);
  RgbImage image = renderer.Render(tabletop->scene(), "top", width, height);
  if (saliency_ == ui::SaliencyMode::kOff) return image;
  if (!method.policy) {
    method.policy = learn::LoadPolicy(
        (fs::path(session_dir_) / store::Session::CheckpointRelativePath(name)).string());
  }
  // What the policy saw at this step: the world's own camera image of the same pose.
  const worlds::Observation seen = tabletop->Observe();
  const probe::SaliencyMap map = saliency_ == ui::SaliencyMode::kGradient
                                     ? probe::GradientSaliency(*method.policy, seen.x, seen.y)
                                     : probe::OcclusionSaliency(*method.policy, seen.x, seen.y);
  return probe::OverlaySaliency(image, map);
}

void RolloutPlayback::Fill(std::vector<ui::RolloutView>& views, worlds::SceneRenderer& renderer,
                           int width, int height) {
  for (ui::RolloutView& view : views) {
    auto it = methods_.find(view.method);
    if (it == methods_.end() || it->second.file.NumScenarios() == 0) continue;
    Method& method = it->second;
    const store::ScenarioReplay& scenario = Scenario(method);
    const int frame = std::min(frame_, static_cast<int>(scenario.states.size()) - 1);
    if (method.image_frame != frame) {
      method.image_frame = frame;
      method.image = Draw(it->first, method, renderer, width, height);
      ++method.image_id;
    }
    view.has_replay = true;
    view.scenario = method.image_scenario;
    view.frame = frame;
    view.frames = static_cast<int>(scenario.states.size());
    view.scenario_seed = scenario.seed;
    view.scenario_metric = scenario.metric;
    view.scenario_succeeded = scenario.succeeded;
    view.frame_image = method.image;
    view.frame_id = method.image_id;
  }
}

}  // namespace recon::studio
