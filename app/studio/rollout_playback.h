#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/learn/policy.h"
#include "engine/store/manifest.h"
#include "engine/store/rollout_replay.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/world.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The Rollouts screen's playback: each method's recorded rollout of the same test scene
/// (rollouts/<method>.replay.h5), drawn a step at a time through the live view's renderer, so
/// Baseline and RECON can be watched side by side and stepped frame by frame. Cell thread only.
class RolloutPlayback {
 public:
  explicit RolloutPlayback(store::SessionManifest manifest, std::string session_dir);

  /// (Re)opens the methods' replay files, e.g. after a rollout run rewrote them; keeps the scene
  /// and step shown when they still exist. UserError naming a damaged file.
  void Reload();
  /// Shows step `frame` of test scene `scenario` (both clamped to what exists) and pauses.
  void Show(int scenario, int frame);
  /// Starts or pauses playing at the control rate from `now`; playing from the last step starts
  /// over.
  void SetPlaying(bool playing, std::chrono::steady_clock::time_point now);
  /// Advances a playing playback by one step per control period; stops at the last step.
  void Tick(std::chrono::steady_clock::time_point now);
  bool playing() const { return playing_; }
  /// Lays which pixels drive each method's action over its frames (its model now, on the frames
  /// of its rollouts); redraws the frames shown.
  void SetSaliency(ui::SaliencyMode mode);

  /// Fills each view whose method has a replay with the scene, the step and its picture
  /// (rendered only when the step shown changed).
  void Fill(std::vector<ui::RolloutView>& views, worlds::SceneRenderer& renderer, int width,
            int height);

 private:
  struct Method {
    store::RolloutReplayFile file;
    std::optional<learn::Policy> policy;            ///< loaded for the saliency, on first use
    std::optional<store::ScenarioReplay> scenario;  ///< the scene being shown, read on demand
    RgbImage image;
    int image_scenario = -1, image_frame = -1;
    uint64_t image_id = 0;
  };
  /// Steps in the scene shown (the longest of the methods').
  int Frames();
  const store::ScenarioReplay& Scenario(Method& method);

  store::SessionManifest manifest_;
  std::string session_dir_;
  std::map<std::string, Method> methods_;
  std::unique_ptr<worlds::World> world_;  ///< drawn into, never stepped
  /// The frame drawn, with the saliency of `method`'s model over it when it is on.
  RgbImage Draw(const std::string& name, Method& method, worlds::SceneRenderer& renderer, int width,
                int height);

  ui::SaliencyMode saliency_ = ui::SaliencyMode::kOff;
  int scenario_ = 0, frame_ = 0;
  bool playing_ = false;
  std::chrono::steady_clock::time_point next_step_;
};

}  // namespace recon::studio
