#pragma once

// The three networks as data: layer shapes and where each layer's weights live in the one flat
// parameter buffer. Everything that trains, runs or stores a model works from this plan.

#include <cstdint>
#include <vector>

#include "engine/core/dataset.h"
#include "engine/core/rng.h"
#include "engine/learn/learner.h"

namespace recon::learn {

enum class Activation { kNone, kRelu, kTanh };

/// The longest action chunk a policy may predict (NetworkConfig::action_chunk): 10 s at 10 Hz.
constexpr int kMaxActionChunk = 100;
/// The feature gate's initial output bias: sigmoid(2) = 0.88, open, so the policy first learns
/// to use the features and the gate margin then shuts them out where they do not help.
constexpr float kGateInitialBias = 2.0f;

/// A fully connected layer y = act(W x + bias); W is row-major [out][in] (PyTorch's layout).
/// `weight` and `bias` are offsets into the flat parameter buffer.
struct LinearLayer {
  int in = 0, out = 0;
  Activation activation = Activation::kNone;
  int64_t weight = 0, bias = 0;
};

/// conv(kernel, valid) + bias, then 2x2 max-pool (floor), then ReLU. W is [out][in][k][k].
struct ConvLayer {
  int in_channels = 0, out_channels = 0, kernel = 0;
  int in_h = 0, in_w = 0;      // input plane
  int out_h = 0, out_w = 0;    // convolution output (valid part)
  int pool_h = 0, pool_w = 0;  // after pooling
  int64_t weight = 0, bias = 0;
};

/// The spatial softmax after the last convolution block (NetworkConfig::spatial_softmax): per
/// channel, a softmax over its h x w plane of f / T, and the expected pixel coordinates under it.
/// Output row: [x_0, y_0, x_1, y_1, ...], x across columns and y across rows, both from -1 at the
/// first pixel's centre to +1 at the last's. T is stored as log T (one float), which keeps it
/// positive under any Adam step and makes its steps relative: starts at 0, i.e. T = 1.
struct SpatialSoftmaxLayer {
  int channels = 0, h = 0, w = 0;
  int64_t log_temperature = 0;  ///< offset of log T in the flat parameter buffer
};

/// The feature net (CNN on the image y, or MLP on [x, y] for a vector y), the policy on
/// [x, phi] with a [mean | log-variance] head of 2 u values, and for RECON the beacon net on phi
/// with a head of 2 d values.
struct Architecture {
  DataSpec spec;
  NetworkConfig network;
  Method method = Method::kRecon;
  std::vector<ConvLayer> convs;      // empty for a vector y
  bool spatial_softmax = false;      // image only; then `keypoints` feeds `feature`
  SpatialSoftmaxLayer keypoints;     // laid out after the convolutions, before `feature`
  std::vector<LinearLayer> feature;  // after the convolutions, or the whole MLP
  std::vector<LinearLayer> policy;   // last layer is the head
  std::vector<LinearLayer> beacon;   // empty for the Baseline
  std::vector<LinearLayer> gate;     // the feature gate on x (one output, before its sigmoid)
  int64_t num_params = 0;

  bool image() const { return spec.YIsImage(); }
  /// Values of one policy target row: u_dim times the action chunk.
  int action_width() const { return spec.u_dim * network.action_chunk; }
  int feature_dim() const { return network.feature_dim; }
  bool has_beacon_net() const { return !beacon.empty(); }
  bool has_gate() const { return !gate.empty(); }
};

/// Lays out the networks. UserError if the configuration cannot be built for these shapes (for
/// example an image too small for the convolutions).
Architecture BuildArchitecture(const DataSpec& spec, const NetworkConfig& network, Method method);

/// A run of parameters in the flat buffer: [offset, offset + size).
struct ParamRange {
  int64_t offset = 0, size = 0;
};

/// Where the weights are (TrainConfig::weight_decay): every linear layer's W and every
/// convolution's kernel, in buffer order; biases and the spatial softmax's temperature are not.
std::vector<ParamRange> WeightRanges(const Architecture& arch);

/// Multiplies every parameter in `ranges` by `factor` (weight decay's shrink).
void ScaleRanges(const std::vector<ParamRange>& ranges, float factor, float* params);

/// The authors' initialisation: Xavier-uniform weights and zero biases for linear layers,
/// PyTorch's default for convolutions (kaiming-uniform with a = sqrt(5), i.e. U(+-1/sqrt(fan_in))
/// for weights and biases). All draws come from `rng`, so a seed fixes the model. The spatial
/// softmax's temperature starts at 1 and draws nothing. The feature gate is drawn last (so a
/// model without it draws what it always did) and starts open: its output bias is
/// kGateInitialBias.
void InitializeParameters(const Architecture& arch, Rng& rng, float* params);

}  // namespace recon::learn
