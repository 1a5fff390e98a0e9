#include "engine/experiments/recipe.h"

namespace recon::experiments {

WorldRecipe RecipeForWorld(const std::string& world, bool images_are_bytes) {
  WorldRecipe recipe;
  const bool arm = world == "bintransfer" || world == "tabletop" || world == "tabletop-state";
  recipe.train.restart_rule = !arm && world != "imported";
  if (arm) recipe.network.policy_hidden = {128, 128};
  if (images_are_bytes) recipe.network.image_scale = 1.0f / 255.0f;
  return recipe;
}

}  // namespace recon::experiments
