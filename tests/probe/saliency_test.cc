// Saliency maps: occlusion finds the pixels a policy reads (a hand-made one that reads four
// pixels); the input-gradient map is the norm of Policy::ActionImageJacobian over the action
// and the channels, for a real (untrained) policy of a fixed seed.

#include "engine/probe/saliency.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/learn/architecture.h"
#include "engine/learn/learner.h"
#include "engine/learn/policy_impl.h"
#include "engine/learn/target_scaling.h"

namespace recon::probe {
namespace {

constexpr int kSize = 20;

/// Reads only the red channel of the 2 x 2 pixels at rows 4-5, columns 12-13.
std::vector<std::vector<float>> ReadsFourPixels(const std::vector<std::vector<float>>&,
                                                const std::vector<std::vector<float>>& ys) {
  std::vector<std::vector<float>> out;
  for (const auto& y : ys) {
    float sum = 0;
    for (int r = 4; r < 6; ++r) {
      for (int c = 12; c < 14; ++c) sum += y[static_cast<size_t>(r) * kSize + c];
    }
    out.push_back({sum / 100.0f, 0.0f});
  }
  return out;
}

std::vector<float> Image(uint64_t seed) {
  Rng rng(seed);
  std::vector<float> y(3 * kSize * kSize);
  for (float& v : y) v = static_cast<float>(rng.Uniform(0, 255));
  return y;
}

TEST(SaliencyTest, OcclusionFindsThePixelsAPolicyReadsAndNothingElse) {
  const SaliencyMap map = OcclusionSaliency(ReadsFourPixels, kSize, {0.0f}, Image(3), 4, 2);
  ASSERT_EQ(map.width, kSize);
  ASSERT_EQ(map.value.size(), static_cast<size_t>(kSize * kSize));
  EXPECT_GT(map.max, 0.0f);
  for (int r = 0; r < kSize; ++r) {
    for (int c = 0; c < kSize; ++c) {
      const float v = map.value[static_cast<size_t>(r) * kSize + c];
      // A patch covering a pixel also covers (at most) 3 pixels either way of it.
      const bool near = r >= 4 - 3 && r <= 5 + 3 && c >= 12 - 3 && c <= 13 + 3;
      if (!near) {
        EXPECT_EQ(v, 0.0f) << r << ", " << c;
      }
    }
  }
  EXPECT_EQ(map.value[4 * kSize + 12], map.max);  // the pixel read is among the most salient
  EXPECT_THROW(OcclusionSaliency(ReadsFourPixels, kSize, {0.0f}, Image(3), 0, 2), UserError);
  EXPECT_THROW(OcclusionSaliency(ReadsFourPixels, kSize, {0.0f}, Image(3), 21, 2), UserError);
  EXPECT_THROW(OcclusionSaliency(ReadsFourPixels, kSize, {0.0f}, std::vector<float>(10), 4, 2),
               UserError);
}

TEST(SaliencyTest, TheGradientMapIsTheJacobiansNormPerPixel) {
  const DataSpec spec{2, {3, 32, 32}, 2, 3};
  learn::NetworkConfig network;
  network.conv_channels = {4, 6};
  network.image_scale = 1.0f / 255.0f;
  const learn::Architecture arch = learn::BuildArchitecture(spec, network, learn::Method::kRecon);
  std::vector<float> params(static_cast<size_t>(arch.num_params));
  Rng rng(8);
  learn::InitializeParameters(arch, rng, params.data());
  const learn::Policy policy(
      std::make_shared<learn::PolicyImpl>(arch, params, learn::TargetScaling::Identity(spec)));
  Rng image_rng(9);
  std::vector<float> y(3 * 32 * 32);
  for (float& v : y) v = static_cast<float>(image_rng.Uniform(0, 255));
  const std::vector<float> x = {0.2f, 0.1f};
  const SaliencyMap map = GradientSaliency(policy, x, y);
  const auto jacobian = policy.ActionImageJacobian(x, y);
  ASSERT_EQ(map.value.size(), 32u * 32u);
  for (size_t p : {0ul, 100ul, 517ul, 1023ul}) {
    double sum = 0;
    for (const auto& row : jacobian) {
      for (size_t c = 0; c < 3; ++c) sum += double(row[c * 1024 + p]) * row[c * 1024 + p];
    }
    EXPECT_NEAR(map.value[p], std::sqrt(sum), 1e-6 + 1e-5 * std::sqrt(sum)) << p;
  }
  EXPECT_GT(map.max, 0.0f);
  // Occlusion on the same policy covers the whole image.
  const SaliencyMap occluded = OcclusionSaliency(policy, x, y, 8, 4);
  EXPECT_EQ(occluded.value.size(), 32u * 32u);
  EXPECT_GT(occluded.max, 0.0f);
}

TEST(SaliencyTest, TheOverlayColoursTheCentredSquareByValueAndLeavesTheRestAlone) {
  RgbImage view{8, 4, std::vector<uint8_t>(8 * 4 * 3, 100)};
  SaliencyMap map;
  map.width = map.height = 2;
  map.value = {0.0f, 1.0f, 0.0f, 0.0f};  // the top right quarter of the policy's image
  map.max = 1.0f;
  const RgbImage out = OverlaySaliency(view, map);
  ASSERT_EQ(out.rgb.size(), view.rgb.size());
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 8; ++c) {
      const bool salient = r < 2 && c >= 4 && c < 6;  // the centred 4 x 4 square, its top right
      const uint8_t* px = out.Pixel(r, c);
      if (salient) {
        EXPECT_NE(px[0], 100) << r << ", " << c;
      } else {
        EXPECT_EQ(px[0], 100) << r << ", " << c;
        EXPECT_EQ(px[2], 100) << r << ", " << c;
      }
    }
  }
  map.max = 0.0f;  // nothing salient: the view unchanged
  EXPECT_EQ(OverlaySaliency(view, map).rgb, view.rgb);
}

}  // namespace
}  // namespace recon::probe
