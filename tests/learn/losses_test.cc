// The two head losses against their closed forms, evaluated by hand in double precision, and
// their gradients against central finite differences.

#include "engine/learn/losses.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace recon::learn {
namespace {

// Two samples, two dimensions: rows are [mean0 mean1 | logvar0 logvar1].
const std::vector<float> kHead = {0.5f, -1.0f, 0.2f,  -0.3f,  //
                                  2.0f, 0.0f,  -1.5f, 0.7f};
const std::vector<float> kTarget = {1.0f, -0.5f,  //
                                    1.0f, 0.25f};
const std::vector<float> kNoise = {0.3f, -1.2f,  //
                                   0.8f, 0.1f};

// d loss / d head[i] by central differences in float, for comparison with the analytic grads.
void ExpectGradientMatchesDifferences(const std::function<float(const float*)>& loss,
                                      const std::vector<float>& grad) {
  for (size_t i = 0; i < kHead.size(); ++i) {
    std::vector<float> plus = kHead, minus = kHead;
    const float h = 1e-3f;
    plus[i] += h;
    minus[i] -= h;
    const double numeric = (loss(plus.data()) - loss(minus.data())) / (2.0 * h);
    EXPECT_NEAR(grad[i], numeric, 2e-3 * std::max(1.0, std::abs(numeric))) << "element " << i;
  }
}

TEST(LossesTest, GaussianNllMatchesClosedFormAndGradient) {
  double expected = 0;
  for (int b = 0; b < 2; ++b) {
    for (int d = 0; d < 2; ++d) {
      const double mean = kHead[b * 4 + d], logvar = kHead[b * 4 + 2 + d], t = kTarget[b * 2 + d];
      expected += 0.5 * (std::log(2 * M_PI) + logvar + (t - mean) * (t - mean) * std::exp(-logvar));
    }
  }
  expected /= 2;  // mean over the batch of per-sample sums
  std::vector<float> grad(kHead.size());
  const float weight = 1.5f;
  EXPECT_NEAR(GaussianNll(kHead.data(), kTarget.data(), 2, 2, weight, grad.data()), expected,
              1e-6 * std::abs(expected));
  // The weight scales the gradient, not the returned loss.
  for (float& g : grad) g /= weight;
  ExpectGradientMatchesDifferences(
      [](const float* head) { return GaussianNll(head, kTarget.data(), 2, 2, 1.0f, nullptr); },
      grad);
  // Hand-checked element: d/dmean of sample 0, dim 0 = (mean - t) * exp(-logvar) / batch.
  EXPECT_NEAR(grad[0], (0.5 - 1.0) * std::exp(-0.2) / 2, 1e-6);
  EXPECT_NEAR(HeadLoss(LossKind::kNll, kHead.data(), kTarget.data(), nullptr, 2, 2, 1, nullptr),
              expected, 1e-6 * std::abs(expected));
}

// TrainConfig::nll_min_std: a log-variance below the floor counts as the floor and gets no
// gradient; one above it counts as itself. The head's logvars are 0.2, -0.3, -1.5 and 0.7; a
// floor at -0.5 holds only the third.
TEST(LossesTest, GaussianNllHoldsALogVarianceBelowTheFloorAtIt) {
  const float floor_value = -0.5f;
  const float floor[2] = {floor_value, floor_value};
  double expected = 0;
  for (int b = 0; b < 2; ++b) {
    for (int d = 0; d < 2; ++d) {
      const double mean = kHead[b * 4 + d], t = kTarget[b * 2 + d];
      const double logvar = std::max<double>(kHead[b * 4 + 2 + d], floor_value);
      expected += 0.5 * (std::log(2 * M_PI) + logvar + (t - mean) * (t - mean) * std::exp(-logvar));
    }
  }
  expected /= 2;
  std::vector<float> grad(kHead.size());
  EXPECT_NEAR(GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, grad.data(), floor), expected,
              1e-6 * std::abs(expected));
  EXPECT_EQ(grad[6], 0.0f);  // sample 1's first logvar (-1.5) is held at the floor
  EXPECT_NE(grad[2], 0.0f);  // the others are free
  EXPECT_NE(grad[7], 0.0f);
  // The mean's gradient uses the floored variance: (mean - t) * exp(-floor) / batch.
  EXPECT_NEAR(grad[4], (2.0 - 1.0) * std::exp(0.5) / 2, 1e-6);
  // Away from the floor's kink, the gradient is the loss's slope.
  ExpectGradientMatchesDifferences(
      [&floor](const float* head) {
        return GaussianNll(head, kTarget.data(), 2, 2, 1.0f, nullptr, floor);
      },
      grad);
  // The default is no floor, and HeadLoss passes the floor on.
  EXPECT_NEAR(
      HeadLoss(LossKind::kNll, kHead.data(), kTarget.data(), nullptr, 2, 2, 1, nullptr, floor),
      expected, 1e-6 * std::abs(expected));
  EXPECT_NE(GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, nullptr),
            GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, nullptr, floor));
}

// TrainConfig::action_min_std: floors per dimension. A floor on dimension 1 only (above both of
// its logvars, -0.3 and 0.7) leaves dimension 0's terms and gradients exactly as without one.
TEST(LossesTest, GaussianNllFloorsEachDimensionByItsOwnFloor) {
  const float none = -std::numeric_limits<float>::infinity();
  const float floor[2] = {none, 1.0f};
  std::vector<float> free_grad(kHead.size()), grad(kHead.size());
  const float free_loss = GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, free_grad.data());
  const float loss = GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, grad.data(), floor);
  double expected = 0;
  for (int b = 0; b < 2; ++b) {
    for (int d = 0; d < 2; ++d) {
      const double mean = kHead[b * 4 + d], t = kTarget[b * 2 + d];
      const double logvar = d == 1 ? 1.0 : kHead[b * 4 + 2 + d];
      expected += 0.5 * (std::log(2 * M_PI) + logvar + (t - mean) * (t - mean) * std::exp(-logvar));
    }
  }
  EXPECT_NEAR(loss, expected / 2, 1e-6 * std::abs(expected));
  EXPECT_NE(loss, free_loss);
  for (int b = 0; b < 2; ++b) {
    EXPECT_EQ(grad[b * 4 + 0], free_grad[b * 4 + 0]) << b;  // dimension 0's mean
    EXPECT_EQ(grad[b * 4 + 2], free_grad[b * 4 + 2]) << b;  // and its logvar
    EXPECT_EQ(grad[b * 4 + 3], 0.0f) << b;                  // dimension 1's logvar is held
    EXPECT_NE(grad[b * 4 + 1], free_grad[b * 4 + 1]) << b;  // its mean weighed by exp(-1)
  }
  // Floors of -infinity everywhere are no floors, bitwise.
  const float nones[2] = {none, none};
  EXPECT_EQ(GaussianNll(kHead.data(), kTarget.data(), 2, 2, 1.0f, nullptr, nones), free_loss);
}

// The policy head's floors: one per dimension of a chunk of actions (u_dim actions per chunk
// step, as the training targets are laid out), the higher of nll_min_std and action_min_std.
TEST(LossesTest, PolicyFloorsRepeatEachActionsFloorOverTheChunk) {
  TrainConfig train;
  for (float v : train.PolicyMinLogVar(3, 2)) EXPECT_TRUE(std::isinf(v) && v < 0);
  EXPECT_EQ(train.PolicyMinLogVar(3, 2).size(), 6u);
  train.action_min_std = {0.0, 0.0, 0.2};  // the last action only
  const std::vector<float> floors = train.PolicyMinLogVar(3, 2);
  ASSERT_EQ(floors.size(), 6u);
  for (int j : {0, 1, 3, 4}) EXPECT_TRUE(std::isinf(floors[j])) << j;
  for (int j : {2, 5}) EXPECT_NEAR(floors[j], 2.0 * std::log(0.2), 1e-6) << j;
  train.nll_min_std = 0.1;  // under the action's floor there, alone elsewhere
  const std::vector<float> both = train.PolicyMinLogVar(3, 2);
  for (int j : {0, 1, 3, 4}) EXPECT_NEAR(both[j], 2.0 * std::log(0.1), 1e-6) << j;
  for (int j : {2, 5}) EXPECT_NEAR(both[j], 2.0 * std::log(0.2), 1e-6) << j;
  train.nll_min_std = 0.5;  // above it: the higher floor holds
  for (float v : train.PolicyMinLogVar(3, 2)) EXPECT_NEAR(v, 2.0 * std::log(0.5), 1e-6);
}

TEST(LossesTest, TheFloorIsTwiceTheLogOfTheStandardDeviationAndOffAtZero) {
  TrainConfig train;
  EXPECT_EQ(train.nll_min_std, 0.0);
  EXPECT_TRUE(std::isinf(train.NllMinLogVar()));
  EXPECT_LT(train.NllMinLogVar(), 0.0f);
  train.nll_min_std = 0.1;
  EXPECT_NEAR(train.NllMinLogVar(), 2.0 * std::log(0.1), 1e-6);
}

TEST(LossesTest, MseOfSampleMatchesClosedFormAndGradient) {
  double expected = 0;
  for (int b = 0; b < 2; ++b) {
    for (int d = 0; d < 2; ++d) {
      const double mean = kHead[b * 4 + d], logvar = kHead[b * 4 + 2 + d];
      const double sample = mean + std::exp(0.5 * logvar) * kNoise[b * 2 + d];
      expected += (sample - kTarget[b * 2 + d]) * (sample - kTarget[b * 2 + d]);
    }
  }
  expected /= 4;  // mean over all batch x dim elements (torch mse_loss 'mean')
  std::vector<float> grad(kHead.size());
  EXPECT_NEAR(MseOfSample(kHead.data(), kTarget.data(), kNoise.data(), 2, 2, 1.0f, grad.data()),
              expected, 1e-6 * expected);
  ExpectGradientMatchesDifferences(
      [](const float* head) {
        return MseOfSample(head, kTarget.data(), kNoise.data(), 2, 2, 1.0f, nullptr);
      },
      grad);
  // With zero noise the loss is the MSE of the means, which is also the restart rule's measure.
  const std::vector<float> zero(4, 0.0f);
  EXPECT_NEAR(MseOfSample(kHead.data(), kTarget.data(), zero.data(), 2, 2, 1.0f, nullptr),
              SumSquaredMeanError(kHead.data(), kTarget.data(), 2, 2) / 4, 1e-6);
}

}  // namespace
}  // namespace recon::learn
