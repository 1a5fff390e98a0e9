#pragma once

// Saliency: which pixels of a camera frame drive a policy's action.

#include <functional>
#include <vector>

#include "engine/core/image.h"
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

/// Actions of many observations at once (rows), as Policy::ActBatch gives them.
using ActBatchFunction = std::function<std::vector<std::vector<float>>(
    const std::vector<std::vector<float>>& xs, const std::vector<std::vector<float>>& ys)>;

/// Occlusion saliency: a `patch` x `patch` square of the image's mean colour slid over it by
/// `stride` pixels; a pixel's value is the mean |a(occluded) - a(y)| over the patches that
/// cover it. `y` is 3 x size x size, channels first. UserError for a patch or stride below 1,
/// a patch larger than the image, or an image of another size.
SaliencyMap OcclusionSaliency(const ActBatchFunction& act, int size, const std::vector<float>& x,
                              const std::vector<float>& y, int patch = 8, int stride = 4);
/// The policy's (UserError for one without a camera image).
SaliencyMap OcclusionSaliency(const learn::Policy& policy, const std::vector<float>& x,
                              const std::vector<float>& y, int patch = 8, int stride = 4);

/// `view` with `map` laid over it, a pixel's colour mixed with the project's sequential colour of
/// its saliency (0 to map.max, on a square-root scale) in proportion to it, so unsalient pixels
/// keep their own. `view`
/// comes from the camera the policy saw through, at any size: the policy's square image is its
/// centred square (the same vertical field of view), where the map is drawn, nearest cell.
RgbImage OverlaySaliency(const RgbImage& view, const SaliencyMap& map);

}  // namespace recon::probe
