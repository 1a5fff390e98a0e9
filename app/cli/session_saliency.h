#pragma once

// `recon eval --saliency demo_N`: which pixels drive each trained method's action over a recorded
// demonstration, as one picture kept in the session: the frames the camera recorded (the first
// row) and, one row per method, the same frames with its saliency laid over them. It runs on the
// recorded frames, so a real cell's session has it too.

#include <string>
#include <vector>

#include "engine/store/session.h"

namespace recon::cli {

struct SaliencySheetOptions {
  std::string episode;               ///< a demonstration of the session, "demo_3"
  std::vector<std::string> methods;  ///< empty: every trained method
  bool occlusion = false;            ///< an occlusion map instead of the input gradient
  int frames = 8;                    ///< columns, spread evenly over the demonstration
};

struct SaliencySheet {
  std::string path;               ///< the picture written
  std::vector<int> steps;         ///< the demonstration's step in each column
  std::vector<std::string> rows;  ///< "recorded", then each method's label
};

/// Writes probe/saliency_<episode>.png. Everything is checked before it writes: UserError for an
/// episode that is not one of the session's demonstrations (naming them), a method that is not
/// trained, a policy without a camera image, or fewer than 1 or more than 64 frames.
SaliencySheet WriteSaliencySheet(const store::Session& session,
                                 const SaliencySheetOptions& options);

}  // namespace recon::cli
