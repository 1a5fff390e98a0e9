#pragma once

// Saliency: which pixels of a camera frame drive a policy's action.

#include <vector>

#include "engine/learn/policy.h"

namespace recon::probe {

/// A value per pixel of an S x S image, row-major, and its largest value (for drawing).
struct SaliencyMap {
  int width = 0, height = 0;
  std::vector<float> value;
  float max = 0;
};

/// Input-gradient saliency: per pixel, the norm over the action's components and the pixel's
/// three channels of d a_j / d y (Policy::ActionImageJacobian), in action units per pixel value.
/// UserError for a policy without a camera image.
SaliencyMap GradientSaliency(const learn::Policy& policy, const std::vector<float>& x,
                             const std::vector<float>& y);

/// Occlusion saliency: a `patch` x `patch` square of the image's mean colour slid over it by
/// `stride` pixels; a pixel's value is the mean |a(occluded) - a(y)| over the patches that
/// cover it. UserError for a patch or stride below 1 or a patch larger than the image.
SaliencyMap OcclusionSaliency(const learn::Policy& policy, const std::vector<float>& x,
                              const std::vector<float>& y, int patch = 8, int stride = 4);

}  // namespace recon::probe
