#include "engine/experiments/recipe.h"

namespace recon::experiments {

WorldRecipe RecipeForWorld(const std::string& world, bool images_are_bytes) {
  WorldRecipe recipe;
  const bool arm = world == "bintransfer" || world == "tabletop" || world == "tabletop-state";
  recipe.train.restart_rule = !arm && world != "imported";
  if (arm) recipe.network.policy_hidden = {128, 128};
  // The tabletop's grasp is a discrete, timed event (close on the way down, wait, lift): one
  // action at a time never learnt to close the gripper; a chunk of 10 (1 s) did (docs/results.md).
  if (world == "tabletop" || world == "tabletop-state") recipe.network.action_chunk = 10;
  // Random shifts of up to 4 pixels (DrQ) helped the Baseline's grasp from the camera.
  if (world == "tabletop" && images_are_bytes) recipe.train.random_shift_px = 4;
  if (images_are_bytes) recipe.network.image_scale = 1.0f / 255.0f;
  return recipe;
}

}  // namespace recon::experiments
