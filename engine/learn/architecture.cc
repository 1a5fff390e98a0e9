#include "engine/learn/architecture.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace recon::learn {

namespace {

void Require(bool ok, const std::string& message) {
  if (!ok) throw UserError("network config: " + message);
}

class Layout {
 public:
  int64_t Take(int64_t count) {
    const int64_t offset = size_;
    size_ += count;
    return offset;
  }
  int64_t size() const { return size_; }

 private:
  int64_t size_ = 0;
};

LinearLayer MakeLinear(int in, int out, Activation activation, Layout& layout) {
  LinearLayer layer;
  layer.in = in;
  layer.out = out;
  layer.activation = activation;
  layer.weight = layout.Take(static_cast<int64_t>(in) * out);
  layer.bias = layout.Take(out);
  return layer;
}

// Hidden layers (activation `first` on the first, `rest` on the others), then a linear head.
std::vector<LinearLayer> MakeMlp(int in, const std::vector<int>& hidden, Activation first,
                                 Activation rest, int out, Layout& layout) {
  std::vector<LinearLayer> layers;
  for (size_t i = 0; i < hidden.size(); ++i) {
    layers.push_back(MakeLinear(in, hidden[i], i == 0 ? first : rest, layout));
    in = hidden[i];
  }
  layers.push_back(MakeLinear(in, out, Activation::kNone, layout));
  return layers;
}

void RequirePositive(const std::vector<int>& sizes, const char* name) {
  for (int s : sizes) Require(s > 0, std::string(name) + " entries must be positive");
}

void FillUniform(Rng& rng, double bound, float* out, int64_t count) {
  for (int64_t i = 0; i < count; ++i) out[i] = static_cast<float>(rng.Uniform(-bound, bound));
}

void InitLinear(const LinearLayer& layer, int head_dims, Rng& rng, float* params) {
  // A head stacks two heads of head_dims outputs (mean, log-variance); each is its own layer in
  // the authors' code, so Xavier's fan-out is head_dims, not 2 * head_dims.
  const int fan_out = head_dims > 0 ? head_dims : layer.out;
  const double bound = std::sqrt(6.0 / (layer.in + fan_out));
  FillUniform(rng, bound, params + layer.weight, static_cast<int64_t>(layer.in) * layer.out);
  for (int i = 0; i < layer.out; ++i) params[layer.bias + i] = 0.0f;
}

void InitMlp(const std::vector<LinearLayer>& layers, bool gaussian_head, Rng& rng, float* params) {
  for (size_t i = 0; i < layers.size(); ++i) {
    const bool head = gaussian_head && i + 1 == layers.size();
    InitLinear(layers[i], head ? layers[i].out / 2 : 0, rng, params);
  }
}

}  // namespace

Architecture BuildArchitecture(const DataSpec& spec, const NetworkConfig& network, Method method) {
  const NetworkConfig& n = network;
  Require(n.feature_dim > 0, "feature_dim must be positive");
  RequirePositive(n.policy_hidden, "policy_hidden");
  RequirePositive(n.beacon_hidden, "beacon_hidden");
  Require(n.action_chunk >= 1 && n.action_chunk <= kMaxActionChunk,
          "action_chunk must be between 1 and " + std::to_string(kMaxActionChunk));
  for (size_t i = 0; i < n.ensembled_actions.size(); ++i) {
    const int a = n.ensembled_actions[i];
    Require(a >= 0 && a < spec.u_dim, "ensembled_actions: " + std::to_string(a) +
                                          " is not an action (u has " + std::to_string(spec.u_dim) +
                                          ": 0-" + std::to_string(spec.u_dim - 1) + ")");
    for (size_t j = 0; j < i; ++j) {
      Require(n.ensembled_actions[j] != a,
              "ensembled_actions: action " + std::to_string(a) + " is listed twice");
    }
  }
  Architecture arch;
  arch.spec = spec;
  arch.network = network;
  arch.method = method;
  Layout layout;
  if (spec.YIsImage()) {
    Require(n.conv_kernel > 0, "conv_kernel must be positive");
    Require(std::isfinite(n.image_scale) && n.image_scale > 0, "image_scale must be positive");
    RequirePositive(n.conv_channels, "conv_channels");
    RequirePositive(n.cnn_hidden, "cnn_hidden");
    int channels = static_cast<int>(spec.y_shape[0]);
    int h = static_cast<int>(spec.y_shape[1]), w = static_cast<int>(spec.y_shape[2]);
    for (size_t i = 0; i < n.conv_channels.size(); ++i) {
      ConvLayer conv;
      conv.in_channels = channels;
      conv.out_channels = n.conv_channels[i];
      conv.kernel = n.conv_kernel;
      conv.in_h = h;
      conv.in_w = w;
      conv.out_h = h - n.conv_kernel + 1;
      conv.out_w = w - n.conv_kernel + 1;
      conv.pool_h = conv.out_h / 2;
      conv.pool_w = conv.out_w / 2;
      Require(conv.pool_h > 0 && conv.pool_w > 0,
              "image " + std::to_string(h) + "x" + std::to_string(w) + " at convolution " +
                  std::to_string(i) + " is too small for a " + std::to_string(n.conv_kernel) + "x" +
                  std::to_string(n.conv_kernel) + " kernel and 2x2 pooling");
      conv.weight = layout.Take(static_cast<int64_t>(conv.out_channels) * channels * n.conv_kernel *
                                n.conv_kernel);
      conv.bias = layout.Take(conv.out_channels);
      arch.convs.push_back(conv);
      channels = conv.out_channels;
      h = conv.pool_h;
      w = conv.pool_w;
    }
    int cnn_features = channels * h * w;
    if (n.spatial_softmax) {
      arch.spatial_softmax = true;
      arch.keypoints.channels = channels;
      arch.keypoints.h = h;
      arch.keypoints.w = w;
      arch.keypoints.log_temperature = layout.Take(1);
      cnn_features = 2 * channels;
    }
    arch.feature = MakeMlp(cnn_features, n.cnn_hidden, Activation::kRelu, Activation::kRelu,
                           n.feature_dim, layout);
  } else {
    RequirePositive(n.feature_mlp_hidden, "feature_mlp_hidden");
    arch.feature = MakeMlp(spec.x_dim + static_cast<int>(spec.YSize()), n.feature_mlp_hidden,
                           Activation::kRelu, Activation::kRelu, n.feature_dim, layout);
  }
  arch.policy = MakeMlp(spec.x_dim + n.feature_dim, n.policy_hidden, Activation::kTanh,
                        Activation::kRelu, 2 * spec.u_dim * n.action_chunk, layout);
  if (method == Method::kRecon && spec.b_dim > 0) {
    arch.beacon = MakeMlp(n.feature_dim, n.beacon_hidden, Activation::kTanh, Activation::kTanh,
                          2 * spec.b_dim, layout);
  }
  if (n.has_feature_gate()) {
    RequirePositive(n.feature_gate_hidden, "feature_gate_hidden");
    arch.gate =
        MakeMlp(spec.x_dim, n.feature_gate_hidden, Activation::kTanh, Activation::kTanh, 1, layout);
  }
  arch.num_params = layout.size();
  return arch;
}

std::vector<ParamRange> WeightRanges(const Architecture& arch) {
  std::vector<ParamRange> ranges;
  for (const ConvLayer& conv : arch.convs) {
    ranges.push_back({conv.weight, static_cast<int64_t>(conv.out_channels) * conv.in_channels *
                                       conv.kernel * conv.kernel});
  }
  for (const std::vector<LinearLayer>* mlp :
       {&arch.feature, &arch.policy, &arch.beacon, &arch.gate}) {
    for (const LinearLayer& layer : *mlp) {
      ranges.push_back({layer.weight, static_cast<int64_t>(layer.in) * layer.out});
    }
  }
  std::sort(ranges.begin(), ranges.end(),
            [](const ParamRange& a, const ParamRange& b) { return a.offset < b.offset; });
  return ranges;
}

void ScaleRanges(const std::vector<ParamRange>& ranges, float factor, float* params) {
  for (const ParamRange& r : ranges) {
    float* p = params + r.offset;
    for (int64_t i = 0; i < r.size; ++i) p[i] *= factor;
  }
}

void InitializeParameters(const Architecture& arch, Rng& rng, float* params) {
  for (const ConvLayer& conv : arch.convs) {
    const int fan_in = conv.in_channels * conv.kernel * conv.kernel;
    const double bound = 1.0 / std::sqrt(static_cast<double>(fan_in));
    FillUniform(rng, bound, params + conv.weight, static_cast<int64_t>(conv.out_channels) * fan_in);
    FillUniform(rng, bound, params + conv.bias, conv.out_channels);
  }
  // Set, not drawn: with the layer off the draws, and so every seed's weights, are unchanged.
  if (arch.spatial_softmax) params[arch.keypoints.log_temperature] = 0.0f;
  InitMlp(arch.feature, false, rng, params);
  InitMlp(arch.policy, true, rng, params);
  InitMlp(arch.beacon, true, rng, params);
  if (arch.has_gate()) {
    InitMlp(arch.gate, false, rng, params);
    params[arch.gate.back().bias] = kGateInitialBias;
  }
}

}  // namespace recon::learn
