#pragma once

// A Policy's shared state: the architecture and a private copy of the weights.

#include <mutex>
#include <vector>

#include "engine/learn/aligned_buffer.h"
#include "engine/learn/architecture.h"
#include "engine/learn/model.h"
#include "engine/learn/target_scaling.h"

namespace recon::learn {

class PolicyImpl {
 public:
  PolicyImpl(Architecture arch, const std::vector<float>& params, TargetScaling scaling);

  /// kAction: the first action of the chunk; kActionChunk: all of it (u_dim * action_chunk).
  /// kGate: the feature gate g(x) (one value; 1 without a gate).
  enum class Output { kAction, kActionChunk, kBeacon, kFeatures, kGate };

  /// One row of `output` per observation (action means, beacon means or features). Checks the
  /// sizes of x and y (UserError). Serialised by a mutex: copies of a Policy share this object.
  /// `gates` (optional, actions only): each observation's feature gate g(x), 1 without a gate.
  std::vector<std::vector<float>> Run(Output output, const std::vector<std::vector<float>>& xs,
                                      const std::vector<std::vector<float>>& ys,
                                      std::vector<float>* gates = nullptr);

  /// d a_j / d y for the first action's mean a (in the user's units) of one observation with a
  /// camera image: u_dim rows of YSize() values, per pixel value as recorded (0-255). UserError
  /// for a vector y (no image) or inputs of the wrong size.
  std::vector<std::vector<float>> ActionImageJacobian(const std::vector<float>& x,
                                                      const std::vector<float>& y);

  const Architecture& arch() const { return arch_; }
  const AlignedFloats& params() const { return params_; }
  const TargetScaling& scaling() const { return scaling_; }

 private:
  void RunChunk(Output output, const std::vector<std::vector<float>>& xs,
                const std::vector<std::vector<float>>& ys, size_t begin, int count,
                std::vector<std::vector<float>>& result, std::vector<float>* gates);

  const Architecture arch_;
  const AlignedFloats params_;
  const TargetScaling scaling_;  ///< maps head means back to the units the data was recorded in
  std::mutex mutex_;
  ModelBuffers buffers_;
  AlignedFloats images_;
};

}  // namespace recon::learn
