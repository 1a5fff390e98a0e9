// The spatial-softmax keypoint layer (NetworkConfig::spatial_softmax): where its keypoints land,
// how it changes the architecture, its configuration's JSON, and that a network with it learns.
// Its gradients are checked against LibTorch autograd in gradient_test.cc.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/learn/architecture.h"
#include "engine/learn/config_json.h"
#include "engine/learn/spatial_softmax.h"
#include "tests/learn/test_data.h"

namespace recon::learn {
namespace {

using testing::MakeImageTask;
using testing::SmallImageNet;

// One layer over [batch][channels][h * w] planes with its own log T as the only parameter.
struct Layer {
  SpatialSoftmaxLayer layer;
  std::vector<float> params;
  SpatialSoftmaxBuffers buffers;

  Layer(int batch, int channels, int h, int w, float temperature) {
    layer.channels = channels;
    layer.h = h;
    layer.w = w;
    layer.log_temperature = 0;
    params = {std::log(temperature)};
    buffers.Resize(layer, batch);
  }
  // Keypoint (x, y) of plane `plane` after a forward pass on `input`.
  std::pair<float, float> Run(const std::vector<float>& input, int plane) {
    SpatialSoftmaxForward(layer, params.data(), input.data(), buffers);
    return {buffers.output()[2 * plane], buffers.output()[2 * plane + 1]};
  }
};

TEST(SpatialSoftmaxTest, CoordinatesSpanMinusOneToOneOverPixelCentres) {
  EXPECT_EQ(KeypointCoordinates(5), (std::vector<float>{-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}));
  EXPECT_EQ(KeypointCoordinates(2), (std::vector<float>{-1.0f, 1.0f}));
  EXPECT_EQ(KeypointCoordinates(1), (std::vector<float>{0.0f}));  // one pixel: the centre
}

TEST(SpatialSoftmaxTest, ABrightPixelPullsItsChannelsKeypointOntoIt) {
  // Two samples of 3 channels on 5 rows x 7 columns (not square, so x and y cannot swap
  // unnoticed); each plane has one bright pixel somewhere else.
  const int h = 5, w = 7, channels = 3, batch = 2;
  const int rows[batch][channels] = {{1, 4, 0}, {2, 0, 3}};
  const int cols[batch][channels] = {{5, 0, 6}, {3, 1, 2}};
  std::vector<float> input(batch * channels * h * w, 0.0f);
  for (int b = 0; b < batch; ++b) {
    for (int c = 0; c < channels; ++c) {
      input[((b * channels + c) * h + rows[b][c]) * w + cols[b][c]] = 1.0f;
    }
  }
  auto expected_x = [&](int col) { return -1.0f + 2.0f * col / (w - 1); };
  auto expected_y = [&](int row) { return -1.0f + 2.0f * row / (h - 1); };

  // T = 0.05: the bright logit is 20 above the others, so the softmax is one-hot to 1e-7.
  Layer sharp(batch, channels, h, w, 0.05f);
  for (int b = 0; b < batch; ++b) {
    for (int c = 0; c < channels; ++c) {
      SCOPED_TRACE("sample " + std::to_string(b) + " channel " + std::to_string(c));
      const auto [x, y] = sharp.Run(input, b * channels + c);
      EXPECT_NEAR(x, expected_x(cols[b][c]), 1e-5);
      EXPECT_NEAR(y, expected_y(rows[b][c]), 1e-5);
    }
  }

  // T = 1: e^1 against 34 dim pixels of weight 1 each. The coordinates sum to 0 over the plane,
  // so the keypoint is the pixel's position scaled by its weight less a dim pixel's, over all.
  Layer soft(batch, channels, h, w, 1.0f);
  const float share = (std::exp(1.0f) - 1.0f) / (std::exp(1.0f) + (h * w - 1));
  const auto [x, y] = soft.Run(input, 0);
  EXPECT_NEAR(x, share * expected_x(cols[0][0]), 1e-6);
  EXPECT_NEAR(y, share * expected_y(rows[0][0]), 1e-6);
}

TEST(SpatialSoftmaxTest, UniformPlanesGiveTheCentreAndHugeValuesStayFinite) {
  const int h = 4, w = 6;
  Layer layer(1, 2, h, w, 1.0f);
  std::vector<float> input(2 * h * w, 3.0f);                      // channel 0: flat
  for (int i = 0; i < h * w; ++i) input[h * w + i] = 200.0f * i;  // channel 1: raw-pixel scale
  const auto [cx, cy] = layer.Run(input, 0);
  EXPECT_NEAR(cx, 0.0f, 1e-6);
  EXPECT_NEAR(cy, 0.0f, 1e-6);
  // Logits up to 4600 (exp overflows float beyond 88): all the mass on the last pixel.
  const auto [x, y] = layer.Run(input, 1);
  EXPECT_EQ(x, 1.0f);
  EXPECT_EQ(y, 1.0f);
  // NaN reaches the output (and so the loss, where training reports it) instead of vanishing.
  input[5] = std::nanf("");
  EXPECT_TRUE(std::isnan(layer.Run(input, 0).first));
}

TEST(SpatialSoftmaxTest, ArchitectureReplacesTheFlattenedPlanesByTwoValuesPerChannel) {
  const DataSpec spec{2, {3, 16, 16}, 2, 2};
  NetworkConfig off = SmallImageNet();
  off.conv_channels = {4};  // 16 -> 14 -> 7x7 planes
  NetworkConfig on = off;
  on.spatial_softmax = true;
  const Architecture a = BuildArchitecture(spec, off, Method::kRecon);
  const Architecture b = BuildArchitecture(spec, on, Method::kRecon);
  EXPECT_FALSE(a.spatial_softmax);
  ASSERT_TRUE(b.spatial_softmax);
  EXPECT_EQ(a.feature.front().in, 4 * 7 * 7);
  EXPECT_EQ(b.feature.front().in, 2 * 4);
  EXPECT_EQ(b.keypoints.channels, 4);
  EXPECT_EQ(b.keypoints.h, 7);
  EXPECT_EQ(b.keypoints.w, 7);
  // One temperature, right after the convolutions; the first linear layer shrinks.
  const int hidden = off.cnn_hidden.front();
  EXPECT_EQ(b.keypoints.log_temperature, a.convs.back().bias + 4);
  EXPECT_EQ(b.num_params, a.num_params + 1 - static_cast<int64_t>(4 * 7 * 7 - 2 * 4) * hidden);

  // The convolutions draw first, so they are the same; T starts at exactly 1 whatever the seed.
  std::vector<float> pa(a.num_params), pb(b.num_params);
  Rng ra(3), rb(3);
  InitializeParameters(a, ra, pa.data());
  InitializeParameters(b, rb, pb.data());
  EXPECT_TRUE(std::equal(pa.begin(), pa.begin() + a.convs.back().bias + 4, pb.begin()));
  EXPECT_EQ(pb[b.keypoints.log_temperature], 0.0f);

  // A vector y has no planes: the setting has nothing to act on, like the other CNN settings.
  const Architecture v = BuildArchitecture(DataSpec{2, {6}, 2, 2}, on, Method::kRecon);
  EXPECT_FALSE(v.spatial_softmax);
  EXPECT_EQ(v.num_params,
            BuildArchitecture(DataSpec{2, {6}, 2, 2}, off, Method::kRecon).num_params);
}

TEST(SpatialSoftmaxTest, ConfigJsonStoresTheFlagAndOldConfigsReadAsOff) {
  EXPECT_FALSE(NetworkConfig{}.spatial_softmax);
  NetworkConfig on = SmallImageNet();
  on.spatial_softmax = true;
  EXPECT_EQ(NetworkConfigFromJson(ToJson(on)), on);
  EXPECT_EQ(NetworkConfigFromJson(ToJson(SmallImageNet())), SmallImageNet());
  EXPECT_FALSE(on == SmallImageNet());  // operator== sees the flag

  nlohmann::json j = nlohmann::json::parse(ToJson(on));
  EXPECT_EQ(j.at("spatial_softmax"), true);
  j.erase("spatial_softmax");  // as written before the layer existed
  const NetworkConfig old = NetworkConfigFromJson(j.dump());
  EXPECT_FALSE(old.spatial_softmax);
  EXPECT_EQ(old, SmallImageNet());
  j["spatial_softmax"] = "yes";
  EXPECT_THROW(NetworkConfigFromJson(j.dump()), UserError);
}

TEST(SpatialSoftmaxTest, ANetworkWithKeypointsLearnsWhereTheBlockIs) {
  // u = b - x with b the bright block's position: the policy sees x directly, but b only through
  // the image, and the Baseline learns from the action alone. Ignoring the image, the best it
  // can do is predict b's mean, an error of b's variance (0.34 here).
  const Dataset data = MakeImageTask(12, 64, 16);
  const Dataset fresh = MakeImageTask(99, 200, 16);  // held out
  NetworkConfig network = SmallImageNet();
  network.conv_channels = {8};  // 16 -> 14 -> 7x7 planes, room for keypoints to move in
  network.spatial_softmax = true;
  TrainConfig train;
  train.method = Method::kBaseline;
  train.steps = 3000;
  train.seed = 4;
  Trainer trainer(data, network, train);
  const double before = testing::ActionMse(trainer.policy(), data);  // initial weights
  trainer.Train();
  const double after = testing::ActionMse(trainer.policy(), data);
  const double held_out = testing::ActionMse(trainer.policy(), fresh);
  const std::vector<Sample>& samples = data.demos[0].samples;
  double b_variance = 0;
  for (int i = 0; i < 2; ++i) {
    double sum = 0, sum_sq = 0;
    for (const Sample& s : samples) {
      sum += s.b[i];
      sum_sq += s.b[i] * s.b[i];
    }
    const double mean = sum / samples.size();
    b_variance += 0.5 * (sum_sq / samples.size() - mean * mean);
  }
  RecordProperty("action_mse_before", std::to_string(before));
  RecordProperty("action_mse_after", std::to_string(after));
  RecordProperty("action_mse_held_out", std::to_string(held_out));
  EXPECT_GT(before, b_variance);
  // Measured: 0.0032 on the training data, 0.040 held out. Random convolutions already give
  // keypoints that follow a bright block, so even with no gradient reaching them (the layer's
  // input gradient zeroed) the linear layers get to 0.022 and 0.080 (0.009-0.040 and
  // 0.072-0.105 over 9 data and weight seeds, against 0.0004-0.011 and 0.019-0.053 with it); a
  // gradient of the wrong sign, or keypoints that do not move with the block, do far worse.
  EXPECT_LT(after, 0.01) << "before " << before << ", b variance " << b_variance;
  EXPECT_LT(held_out, 0.06);
}

}  // namespace
}  // namespace recon::learn
