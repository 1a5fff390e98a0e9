#pragma once

namespace recon::ui {

/// Which pixels drive the action, laid over the frames played back (rollouts, trials): the
/// input gradient's saliency, an occlusion map, or none.
enum class SaliencyMode { kOff, kGradient, kOcclusion };

}  // namespace recon::ui
