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

/// The feature net (CNN on the image y, or MLP on [x, y] for a vector y), the policy on
/// [x, phi] with a [mean | log-variance] head of 2 u values, and for RECON the beacon net on phi
/// with a head of 2 d values.
struct Architecture {
  DataSpec spec;
  NetworkConfig network;
  Method method = Method::kRecon;
  std::vector<ConvLayer> convs;      // empty for a vector y
  std::vector<LinearLayer> feature;  // after the convolutions, or the whole MLP
  std::vector<LinearLayer> policy;   // last layer is the head
  std::vector<LinearLayer> beacon;   // empty for the Baseline
  int64_t num_params = 0;

  bool image() const { return spec.YIsImage(); }
  int feature_dim() const { return network.feature_dim; }
  bool has_beacon_net() const { return !beacon.empty(); }
};

/// Lays out the networks. UserError if the configuration cannot be built for these shapes (for
/// example an image too small for the convolutions).
Architecture BuildArchitecture(const DataSpec& spec, const NetworkConfig& network, Method method);

/// The authors' initialisation: Xavier-uniform weights and zero biases for linear layers,
/// PyTorch's default for convolutions (kaiming-uniform with a = sqrt(5), i.e. U(+-1/sqrt(fan_in))
/// for weights and biases). All draws come from `rng`, so a seed fixes the model.
void InitializeParameters(const Architecture& arch, Rng& rng, float* params);

}  // namespace recon::learn
