// The policy's input gradient (Policy::ActionImageJacobian, what a saliency map is made of)
// against central finite differences of Act, on untrained models of fixed seeds: plain, with a
// spatial softmax, with a feature gate, and as an ensemble.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/learn/architecture.h"
#include "engine/learn/learner.h"
#include "engine/learn/policy.h"
#include "engine/learn/policy_impl.h"
#include "engine/learn/target_scaling.h"

namespace recon::learn {
namespace {

// 32 x 32: two 5 x 5 convolutions with pooling leave 5 x 5 planes, so a spatial softmax has
// places to choose between (on 16 x 16 it would see one, and no image would matter).
constexpr int kSize = 32;

Policy RandomPolicy(const NetworkConfig& network, uint64_t seed) {
  const DataSpec spec{2, {3, kSize, kSize}, 2, 3};
  const Architecture arch = BuildArchitecture(spec, network, Method::kRecon);
  std::vector<float> params(static_cast<size_t>(arch.num_params));
  Rng rng(seed);
  InitializeParameters(arch, rng, params.data());
  TargetScaling scaling = TargetScaling::Identity(spec);
  scaling.u_scale = {2.0f, 0.5f, 1.5f};  // the gradient is in the user's units
  scaling.u_offset = {0.1f, -0.3f, 0.0f};
  return Policy(std::make_shared<PolicyImpl>(arch, params, scaling));
}

std::vector<float> Image(uint64_t seed) {
  Rng rng(seed);
  std::vector<float> y(3 * kSize * kSize);
  for (float& v : y) v = static_cast<float>(rng.Uniform(0, 255));
  return y;
}

/// Every action component's gradient at 24 pixel values (the 12 largest and 12 drawn) agrees
/// with (a(y + h) - a(y - h)) / 2h.
void ExpectMatchesFiniteDifferences(const Policy& policy, uint64_t seed) {
  const std::vector<float> x = {0.3f, -0.2f}, y = Image(seed);
  const std::vector<std::vector<float>> jacobian = policy.ActionImageJacobian(x, y);
  ASSERT_EQ(jacobian.size(), 3u);
  double largest = 0;
  for (const std::vector<float>& row : jacobian) {
    ASSERT_EQ(row.size(), y.size());
    for (float v : row) largest = std::max(largest, std::abs(static_cast<double>(v)));
  }
  ASSERT_GT(largest, 0.0) << "the action does not depend on the image at all";
  std::vector<size_t> pixels(y.size());
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = i;
  std::partial_sort(pixels.begin(), pixels.begin() + 12, pixels.end(), [&](size_t a, size_t b) {
    return std::abs(jacobian[0][a]) > std::abs(jacobian[0][b]);
  });
  pixels.resize(12);
  Rng rng(seed + 1);
  for (int i = 0; i < 12; ++i) pixels.push_back(rng.UniformInt(static_cast<int>(y.size())));
  constexpr float kStep = 0.25f;  // in pixel values (0-255)
  for (size_t pixel : pixels) {
    std::vector<float> up = y, down = y;
    up[pixel] += kStep;
    down[pixel] -= kStep;
    const std::vector<float> a_up = policy.Act(x, up), a_down = policy.Act(x, down);
    for (size_t j = 0; j < a_up.size(); ++j) {
      const double numeric = (a_up[j] - a_down[j]) / (2.0 * kStep);
      EXPECT_NEAR(jacobian[j][pixel], numeric, 2e-3 * largest + 1e-6)
          << "component " << j << ", pixel value " << pixel;
    }
  }
}

TEST(ActionImageJacobianTest, MatchesFiniteDifferencesOfTheAction) {
  NetworkConfig network;
  network.conv_channels = {4, 6};
  network.image_scale = 1.0f / 255.0f;
  ExpectMatchesFiniteDifferences(RandomPolicy(network, 3), 11);
}

TEST(ActionImageJacobianTest, MatchesFiniteDifferencesWithASpatialSoftmaxAndAFeatureGate) {
  NetworkConfig network;
  network.conv_channels = {4, 6};
  network.image_scale = 1.0f / 255.0f;
  network.spatial_softmax = true;
  ExpectMatchesFiniteDifferences(RandomPolicy(network, 4), 12);
  network.feature_gate_hidden = {8};
  ExpectMatchesFiniteDifferences(RandomPolicy(network, 5), 13);
}

TEST(ActionImageJacobianTest, AnEnsemblesIsItsMembersMeanAndAVectorPolicyHasNone) {
  NetworkConfig network;
  network.conv_channels = {4, 6};
  network.image_scale = 1.0f / 255.0f;
  const Policy a = RandomPolicy(network, 6), b = RandomPolicy(network, 7);
  const Policy both = Policy::Ensemble({a, b});
  ExpectMatchesFiniteDifferences(both, 14);
  const std::vector<float> x = {0.1f, 0.2f}, y = Image(15);
  const auto ja = a.ActionImageJacobian(x, y), jb = b.ActionImageJacobian(x, y),
             jboth = both.ActionImageJacobian(x, y);
  for (size_t i = 0; i < y.size(); i += 97) {
    EXPECT_NEAR(jboth[1][i], 0.5f * (ja[1][i] + jb[1][i]), 1e-6f);
  }

  const DataSpec vector_spec{2, {5}, 2, 2};
  const Architecture arch = BuildArchitecture(vector_spec, NetworkConfig{}, Method::kBaseline);
  std::vector<float> params(static_cast<size_t>(arch.num_params), 0.01f);
  const Policy vector_policy(
      std::make_shared<PolicyImpl>(arch, params, TargetScaling::Identity(vector_spec)));
  try {
    vector_policy.ActionImageJacobian({0, 0}, {0, 0, 0, 0, 0});
    ADD_FAILURE() << "a policy without an image gave a saliency";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("no camera image"), std::string::npos);
  }
}

}  // namespace
}  // namespace recon::learn
