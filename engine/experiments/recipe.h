#pragma once

#include <string>
#include <vector>

#include "engine/learn/learner.h"

namespace recon::experiments {

/// The networks and training settings RECON Studio uses for a world, shared by the experiments
/// and by `recon train` on recorded sessions:
/// - the 2-D worlds: the authors' networks and recipe (restart rule on);
/// - the arm worlds (bintransfer, tabletop): a (128, 128) policy, since a six-joint arm with grasp
///   phases needs more than the authors' 2-D (32, 32); on tabletop a (32, 32) policy did not even
///   repeat a training layout. No restart rule: its thresholds are calibrated to Dynamic 2D's
///   losses and would retrain every run five times;
/// - camera images stored as 0-255 (`images_are_bytes`) are scaled to 0-1 before the CNN (the
///   authors' raw 0-255 was for their 32 x 32 Dynamic 2D drawings, which keep it);
/// - the tabletop predicts chunks of 10 actions (20 from a person's takes), ensembled over steps
///   (ACT), with a (512, 512)
///   policy trained at a learning rate of 1e-3, 7,500 steps from the camera and 15,000 on the
///   true positions (train.steps, train.learning_rate: what `recon experiment`, `recon train`
///   and the studio use unless told otherwise).
/// The feature gate's hidden layers when an option turns it on (NetworkConfig::
/// feature_gate_hidden): the gate only has to tell phases of the task apart from the state.
inline const std::vector<int> kFeatureGateHidden = {32};

struct WorldRecipe {
  learn::NetworkConfig network;
  learn::TrainConfig train;
  /// The action's motion entries (World::ActionNoiseScale's shape: non-zero = motion) when the
  /// recipe leaves a person's pauses out of training (WithoutPauses, engine/core/pauses.h);
  /// empty: every sample is trained on.
  std::vector<float> pause_motion;
};
/// `persons_takes`: the demonstrations are a person's (the keyboard, a gamepad, the simulated
/// person), not the scripted teacher's; the tabletop's recipe then predicts longer chunks.
WorldRecipe RecipeForWorld(const std::string& world, bool images_are_bytes,
                           bool persons_takes = false);

}  // namespace recon::experiments
