// The learner's forward and backward passes against LibTorch autograd on the same weights and
// batch, for every kernel table this CPU can run: outputs, losses and every parameter's gradient
// must agree to float rounding.

#include <gtest/gtest.h>
#include <torch/torch.h>

#include <cmath>
#include <optional>

#include "engine/core/malloc_tuning.h"
#include "engine/learn/architecture.h"
#include "engine/learn/kernels.h"
#include "engine/learn/losses.h"
#include "engine/learn/model.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using testing::MakeImageTask;
using testing::MakeVectorTask;

// The reference: the same networks written with LibTorch operators, weights as views into one
// flat tensor laid out like ours.
class TorchModel {
 public:
  TorchModel(const Architecture& arch, const std::vector<float>& params) : arch_(arch) {
    params_ = torch::tensor(params).requires_grad_(true);
  }

  torch::Tensor Features(const torch::Tensor& x, const torch::Tensor& y) const {
    if (!arch_.image()) return Mlp(arch_.feature, torch::cat({x, y}, 1));
    torch::Tensor h = y * arch_.network.image_scale;
    for (const ConvLayer& c : arch_.convs) {
      const torch::Tensor w = Slice(c.weight, {c.out_channels, c.in_channels, c.kernel, c.kernel});
      h = torch::conv2d(h, w, Slice(c.bias, {c.out_channels}));
      h = torch::max_pool2d(torch::relu(h), 2);  // the authors' order
    }
    if (!arch_.spatial_softmax) return Mlp(arch_.feature, h.flatten(1));
    // Written independently of ours: softmax of f / T over each [h][w] plane, coordinates from
    // linspace, keypoints [x_c, y_c] per channel.
    const SpatialSoftmaxLayer& k = arch_.keypoints;
    const torch::Tensor temperature = torch::exp(Slice(k.log_temperature, {1}));
    const torch::Tensor s =
        torch::softmax(h.flatten(2) / temperature, 2).view({-1, k.channels, k.h, k.w});
    const torch::Tensor xs = torch::linspace(-1, 1, k.w), ys = torch::linspace(-1, 1, k.h);
    const torch::Tensor ex = (s.sum(2) * xs).sum(2), ey = (s.sum(3) * ys).sum(2);
    return Mlp(arch_.feature, torch::stack({ex, ey}, 2).flatten(1));
  }
  torch::Tensor Policy(const torch::Tensor& x, const torch::Tensor& phi) const {
    return Mlp(arch_.policy, torch::cat({x, phi}, 1));
  }
  torch::Tensor Beacon(const torch::Tensor& phi) const { return Mlp(arch_.beacon, phi); }
  torch::Tensor Gate(const torch::Tensor& x) const { return torch::sigmoid(Mlp(arch_.gate, x)); }
  const torch::Tensor& params() const { return params_; }

 private:
  torch::Tensor Slice(int64_t offset, std::vector<int64_t> shape) const {
    int64_t n = 1;
    for (int64_t d : shape) n *= d;
    return params_.narrow(0, offset, n).view(shape);
  }
  torch::Tensor Mlp(const std::vector<LinearLayer>& layers, torch::Tensor h) const {
    for (const LinearLayer& l : layers) {
      h = torch::linear(h, Slice(l.weight, {l.out, l.in}), Slice(l.bias, {l.out}));
      if (l.activation == Activation::kRelu) h = torch::relu(h);
      if (l.activation == Activation::kTanh) h = torch::tanh(h);
    }
    return h;
  }

  const Architecture& arch_;
  torch::Tensor params_;
};

torch::Tensor TorchLoss(LossKind kind, const torch::Tensor& head, const torch::Tensor& target,
                        const torch::Tensor& noise) {
  const int64_t d = target.size(1);
  const torch::Tensor mean = head.narrow(1, 0, d), logvar = head.narrow(1, d, d);
  if (kind == LossKind::kNll) {
    const torch::Tensor nll =
        0.5 * (std::log(2 * M_PI) + logvar + (target - mean).pow(2) * torch::exp(-logvar));
    return nll.sum(1).mean();
  }
  return torch::mse_loss(mean + torch::exp(0.5 * logvar) * noise, target);
}

torch::Tensor Rows(const std::vector<float>& values, int64_t rows, std::vector<int64_t> row_shape) {
  row_shape.insert(row_shape.begin(), rows);
  return torch::tensor(values).view(row_shape);
}

// Max |a - b| must be within `rel` of max |b| (plus a tiny absolute floor).
void ExpectClose(const float* a, const torch::Tensor& b, const std::string& what,
                 double rel = 2e-4) {
  const torch::Tensor bc = b.detach().contiguous().view({-1});
  const float* bp = bc.data_ptr<float>();
  double max_diff = 0, max_ref = 0;
  for (int64_t i = 0; i < bc.numel(); ++i) {
    max_diff = std::max(max_diff, std::abs(static_cast<double>(a[i]) - bp[i]));
    max_ref = std::max(max_ref, std::abs(static_cast<double>(bp[i])));
  }
  EXPECT_LE(max_diff, rel * max_ref + 1e-7) << what << " (max |ref| " << max_ref << ")";
}

struct Case {
  Dataset data;
  NetworkConfig network;
  Method method = Method::kRecon;
  LossKind loss = LossKind::kMseSample;
  int batch = 5;
  std::optional<float> log_temperature;  ///< spatial softmax: replaces the initial log T = 0
};

void CheckAgainstAutograd(const Case& c) {
  const Architecture arch = BuildArchitecture(c.data.spec, c.network, c.method);
  std::vector<float> params(arch.num_params);
  Rng rng(11);
  InitializeParameters(arch, rng, params.data());
  for (float& p : params) p += static_cast<float>(rng.Uniform(-0.05, 0.05));  // biases != 0
  if (c.log_temperature.has_value()) params[arch.keypoints.log_temperature] = *c.log_temperature;

  const DataSpec& s = c.data.spec;
  const int b = c.batch, u = s.u_dim, d = s.b_dim;
  const float scale = arch.image() ? c.network.image_scale : 1.0f;
  std::vector<const Sample*> samples;
  for (const Episode& e : c.data.demos) {
    for (const Sample& sample : e.samples) samples.push_back(&sample);
  }
  std::vector<float> x, y, scaled_y, target_u, target_b, play_x, play_y, scaled_play_y, play_b;
  for (int i = 0; i < b; ++i) {
    const Sample& sample = *samples[i];
    x.insert(x.end(), sample.x.begin(), sample.x.end());
    y.insert(y.end(), sample.y.begin(), sample.y.end());
    for (float v : sample.y) scaled_y.push_back(v * scale);
    target_u.insert(target_u.end(), sample.u.begin(), sample.u.end());
    target_b.insert(target_b.end(), sample.b.begin(), sample.b.end());
    const PlaySample& p = c.data.play[i];
    play_x.insert(play_x.end(), p.x.begin(), p.x.end());
    play_y.insert(play_y.end(), p.y.begin(), p.y.end());
    for (float v : p.y) scaled_play_y.push_back(v * scale);
    play_b.insert(play_b.end(), p.b.begin(), p.b.end());
  }
  std::vector<float> noise_u(b * u), noise_b(b * d), noise_p(b * d);
  for (float& v : noise_u) v = static_cast<float>(rng.Normal());
  for (float& v : noise_b) v = static_cast<float>(rng.Normal());
  for (float& v : noise_p) v = static_cast<float>(rng.Normal());
  const bool recon = c.method == Method::kRecon;
  // margin: the feature gate's (0: the targets are where seeing beats blind at all, a mix).
  const float wa = 1.0f, wb = 1.2f, wp = 0.7f, margin = 0.0f;

  // Ours.
  const int64_t y_size = s.YSize();
  ModelBuffers demo, play;
  demo.Resize(arch, b);
  play.Resize(arch, b);
  demo.x = x;
  play.x = play_x;
  for (int i = 0; i < b; ++i) {
    demo.y[i] = scaled_y.data() + i * y_size;
    play.y[i] = scaled_play_y.data() + i * y_size;
  }
  std::vector<float> grads(arch.num_params, 0.0f), g_u(2 * b * u), g_b(2 * b * d), g_p(2 * b * d);
  ForwardFeatures(arch, params.data(), demo);
  ForwardPolicy(arch, params.data(), demo);
  std::vector<float> g_blind(g_u.size());
  float la = 0;
  std::vector<float> gate_targets;
  if (arch.has_gate()) {
    // Both branches on every sample; the gate's cross-entropy against "seeing pays by more than
    // the margin", whose slope in the logit is g - t (trainer_step.cc).
    for (int i = 0; i < b; ++i) {
      const float seeing = HeadLoss(c.loss, demo.seeing_head() + 2 * i * u, target_u.data() + i * u,
                                    noise_u.data() + i * u, 1, u, wa / b, g_u.data() + 2 * i * u);
      const float blind =
          HeadLoss(c.loss, demo.blind_head() + 2 * i * u, target_u.data() + i * u,
                   noise_u.data() + i * u, 1, u, wa / b, g_blind.data() + 2 * i * u);
      la += seeing / b;
      gate_targets.push_back(blind - seeing > margin ? 1.0f : 0.0f);
      demo.grad_gate[i] = (demo.gate_value[i] - gate_targets.back()) / b;
    }
  } else {
    la =
        HeadLoss(c.loss, demo.policy_head(), target_u.data(), noise_u.data(), b, u, wa, g_u.data());
  }
  float lb = 0, lp = 0;
  if (recon) {
    ForwardBeacon(arch, params.data(), demo);
    lb =
        HeadLoss(c.loss, demo.beacon_head(), target_b.data(), noise_b.data(), b, d, wb, g_b.data());
    ForwardFeatures(arch, params.data(), play);
    ForwardBeacon(arch, params.data(), play);
    lp = HeadLoss(c.loss, play.beacon_head(), play_b.data(), noise_p.data(), b, d, wp, g_p.data());
  }
  Backward(arch, params.data(), g_u.data(), recon ? g_b.data() : nullptr, demo, grads.data(),
           arch.has_gate() ? g_blind.data() : nullptr);
  if (recon) Backward(arch, params.data(), nullptr, g_p.data(), play, grads.data());

  // LibTorch.
  std::vector<int64_t> y_shape = s.y_shape;
  TorchModel ref(arch, params);
  const torch::Tensor tx = Rows(x, b, {s.x_dim}), ty = Rows(y, b, y_shape);
  const torch::Tensor phi = ref.Features(tx, ty);
  const torch::Tensor head_u = ref.Policy(tx, phi);
  const torch::Tensor tu = Rows(target_u, b, {u}), nu = Rows(noise_u, b, {u});
  torch::Tensor loss_a;
  if (arch.has_gate()) {
    // Written from the definition, one sample at a time: both branches' losses, and the gate's
    // binary cross-entropy against where seeing beats blind by more than the margin (a
    // constant target); the acting head the g-mixture of the two branches.
    const torch::Tensor gate = ref.Gate(tx).view({-1});
    const torch::Tensor head_blind = ref.Policy(tx, torch::zeros_like(phi));
    loss_a = torch::zeros({});
    torch::Tensor seeing_mean = torch::zeros({});
    for (int i = 0; i < b; ++i) {
      const torch::Tensor seeing =
          TorchLoss(c.loss, head_u.narrow(0, i, 1), tu.narrow(0, i, 1), nu.narrow(0, i, 1));
      const torch::Tensor blind =
          TorchLoss(c.loss, head_blind.narrow(0, i, 1), tu.narrow(0, i, 1), nu.narrow(0, i, 1));
      const float t = (blind - seeing).item<float>() > margin ? 1.0f : 0.0f;
      EXPECT_EQ(t, gate_targets[i]) << "sample " << i;
      seeing_mean = seeing_mean + seeing / b;
      // The cross-entropy enters the total once, not times wa: divided here, as wa multiplies.
      const torch::Tensor bce = -(t * torch::log(gate[i]) + (1 - t) * torch::log(1 - gate[i]));
      loss_a = loss_a + (seeing + blind) / b + bce / (b * wa);
    }
    EXPECT_NEAR(la, seeing_mean.item<float>(), 1e-4 * std::abs(seeing_mean.item<float>()) + 1e-6);
    ExpectClose(demo.gate_value.data(), gate, "gate");
    ExpectClose(demo.blind_head(), head_blind, "blind head");
    const torch::Tensor g = gate.unsqueeze(1);
    ExpectClose(demo.policy_head(), g * head_u + (1 - g) * head_blind, "acting head");
  } else {
    loss_a = TorchLoss(c.loss, head_u, tu, nu);
  }
  torch::Tensor total = wa * loss_a;
  ExpectClose(demo.phi(), phi, "phi");
  ExpectClose(demo.seeing_head(), head_u, "policy head");
  if (!arch.has_gate()) {  // (gated: checked above, before the penalty)
    EXPECT_NEAR(la, loss_a.item<float>(), 1e-4 * std::abs(loss_a.item<float>()) + 1e-6);
  }
  if (recon) {
    const torch::Tensor head_b = ref.Beacon(phi);
    const torch::Tensor loss_b =
        TorchLoss(c.loss, head_b, Rows(target_b, b, {d}), Rows(noise_b, b, {d}));
    const torch::Tensor pphi = ref.Features(Rows(play_x, b, {s.x_dim}), Rows(play_y, b, y_shape));
    const torch::Tensor head_p = ref.Beacon(pphi);
    const torch::Tensor loss_p =
        TorchLoss(c.loss, head_p, Rows(play_b, b, {d}), Rows(noise_p, b, {d}));
    ExpectClose(demo.beacon_head(), head_b, "beacon head");
    ExpectClose(play.beacon_head(), head_p, "play beacon head");
    EXPECT_NEAR(lb, loss_b.item<float>(), 1e-4 * std::abs(loss_b.item<float>()) + 1e-6);
    EXPECT_NEAR(lp, loss_p.item<float>(), 1e-4 * std::abs(loss_p.item<float>()) + 1e-6);
    total = total + wb * loss_b + wp * loss_p;
  }
  total.backward();
  const torch::Tensor ref_grad = ref.params().grad();
  auto check = [&](int64_t offset, int64_t count, const std::string& name) {
    ExpectClose(grads.data() + offset, ref_grad.narrow(0, offset, count), name);
  };
  for (size_t i = 0; i < arch.convs.size(); ++i) {
    const ConvLayer& l = arch.convs[i];
    check(l.weight, l.bias - l.weight, "conv " + std::to_string(i) + " weight");
    check(l.bias, l.out_channels, "conv " + std::to_string(i) + " bias");
  }
  auto check_mlp = [&](const std::vector<LinearLayer>& layers, const std::string& name) {
    for (size_t i = 0; i < layers.size(); ++i) {
      const LinearLayer& l = layers[i];
      check(l.weight, static_cast<int64_t>(l.in) * l.out, name + std::to_string(i) + " weight");
      check(l.bias, l.out, name + std::to_string(i) + " bias");
    }
  };
  if (arch.spatial_softmax) {
    check(arch.keypoints.log_temperature, 1, "spatial softmax log temperature");
    // A zero gradient would pass the check vacuously.
    EXPECT_NE(grads[arch.keypoints.log_temperature], 0.0f);
  }
  check_mlp(arch.feature, "feature ");
  check_mlp(arch.policy, "policy ");
  check_mlp(arch.beacon, "beacon ");
  check_mlp(arch.gate, "gate ");
  if (arch.has_gate()) {
    // A zero gradient would pass the check vacuously.
    EXPECT_NE(grads[arch.gate.back().bias], 0.0f);
  }
}

class ModelGradientTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    recon::TuneMallocForTraining();
    previous_ = kernels::Kernels().name;
    ASSERT_TRUE(kernels::UseKernels(GetParam()));
  }
  void TearDown() override { kernels::UseKernels(previous_); }

 private:
  std::string previous_;
};

TEST_P(ModelGradientTest, ImageModelsMatchAutograd) {
  {
    SCOPED_TRACE("authors' CNN on 3x32x32, MSE of a sample");
    Case c;
    c.data = MakeImageTask(1, 6, 32, 6);
    c.network.image_scale = 1.0f / 255.0f;
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("odd sizes (15x15, kernel 3, floor pooling), NLL");
    Case c;
    c.data = MakeImageTask(2, 6, 15, 6);
    c.network = testing::SmallImageNet();
    c.network.conv_channels = {5, 7};
    c.loss = LossKind::kNll;
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("Baseline, raw pixel values (image_scale 1)");
    Case c;
    c.data = MakeImageTask(3, 6, 16, 6);
    c.network = testing::SmallImageNet();
    c.network.image_scale = 1.0f;
    c.method = Method::kBaseline;
    CheckAgainstAutograd(c);
  }
}

TEST_P(ModelGradientTest, SpatialSoftmaxModelsMatchAutograd) {
  {
    SCOPED_TRACE("authors' CNN on 3x32x32 (5x5 planes), NLL, T = 1");
    Case c;
    c.data = MakeImageTask(5, 6, 32, 6);
    c.network.image_scale = 1.0f / 255.0f;
    c.network.spatial_softmax = true;
    c.loss = LossKind::kNll;
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("one block on 15x15 (6x6 planes), MSE of a sample, T = 0.4");
    Case c;
    c.data = MakeImageTask(6, 6, 15, 6);
    c.network = testing::SmallImageNet();
    c.network.conv_channels = {5};
    c.network.spatial_softmax = true;
    c.log_temperature = std::log(0.4f);
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("non-square 3x8x32 images (3x15 planes: x and y must not swap), T = 3");
    Case c;
    c.data = MakeImageTask(7, 6, 16, 6);
    c.data.spec.y_shape = {3, 8, 32};  // the same pixels, seen as another shape
    c.network = testing::SmallImageNet();
    c.network.conv_channels = {4};
    c.network.spatial_softmax = true;
    c.log_temperature = std::log(3.0f);
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("Baseline, raw pixel values (nearly one-hot softmax on 2x2 planes)");
    Case c;
    c.data = MakeImageTask(8, 6, 16, 6);
    c.network = testing::SmallImageNet();
    c.network.image_scale = 1.0f;
    c.network.spatial_softmax = true;
    c.method = Method::kBaseline;
    CheckAgainstAutograd(c);
  }
}

TEST_P(ModelGradientTest, FeatureGateMatchesAutograd) {
  {
    SCOPED_TRACE("RECON, authors' CNN on 3x32x32, gate (8, 4), NLL");
    Case c;
    c.data = MakeImageTask(9, 6, 32, 6);
    c.network.image_scale = 1.0f / 255.0f;
    c.network.feature_gate_hidden = {8, 4};
    c.loss = LossKind::kNll;
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("Baseline, keypoints, gate (5), MSE of a sample");
    Case c;
    c.data = MakeImageTask(10, 6, 16, 6);
    c.network = testing::SmallImageNet();
    c.network.spatial_softmax = true;
    c.network.feature_gate_hidden = {5};
    c.method = Method::kBaseline;
    CheckAgainstAutograd(c);
  }
  {
    SCOPED_TRACE("vector y, gate (6)");
    Case c;
    c.data = MakeVectorTask(11, 4, 6);
    c.network.feature_gate_hidden = {6};
    c.loss = LossKind::kNll;
    c.batch = 6;
    CheckAgainstAutograd(c);
  }
}

TEST_P(ModelGradientTest, VectorModelMatchesAutograd) {
  for (LossKind loss : {LossKind::kNll, LossKind::kMseSample}) {
    SCOPED_TRACE(ToString(loss));
    Case c;
    c.data = MakeVectorTask(4, 4, 6);
    c.loss = loss;
    c.batch = 6;
    CheckAgainstAutograd(c);
  }
}

INSTANTIATE_TEST_SUITE_P(Kernels, ModelGradientTest,
                         ::testing::ValuesIn(kernels::AvailableKernels()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

}  // namespace
}  // namespace recon::learn
